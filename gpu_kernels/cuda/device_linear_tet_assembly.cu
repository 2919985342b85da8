// Built with --fmad=false (gpu_kernels/CMakeLists.txt): the corotation and the blocks are the CPU's bits.
#include <cuda_runtime.h>

#include <utility>

#include "device_support.cuh"
#include "gpu_kernels/device_linear_tet_assembly.h"
#include "gpu_kernels/linear_tet_kernels.h"

namespace vp::gpu {
namespace {

// The mesh as device pointers (the layout of LinearTetAssemblyView).
struct MeshArrays {
  int32_t nodes;
  int64_t elements;
  const int32_t* elementNodes;
  const double* restGradients;
  const double* restVolume;
  double lambda, mu;
  const int32_t* rowStart;
  kernels::ElementIncidenceView incidence;
  const int32_t* scatter;
};

__global__ void __launch_bounds__(launch::kThreads)
    corotateKernel(MeshArrays m, const double* positions, double* quat, double* elementForce, double* rotatedGrad) {
  const int64_t e = launch::index();
  if (e >= m.elements) return;
  double x[12];
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) x[3 * a + i] = positions[3 * m.elementNodes[4 * e + a] + i];
  kernels::corotateLinearTet(x, &m.restGradients[12 * e], m.restVolume[e], m.lambda, m.mu, &quat[4 * e],
                             &elementForce[12 * e], &rotatedGrad[12 * e]);
}

__global__ void __launch_bounds__(launch::kThreads)
    gatherKernel(MeshArrays m, const double* elementForce, const double* rotatedGrad, double stiffnessScale,
                 double* values, double* force) {
  const int64_t i = launch::index();
  if (i >= m.nodes) return;
  const auto addBlock = [&](int64_t e, int a, int b, double* block) {
    kernels::addLinearTetBlock(&rotatedGrad[12 * e], &m.restGradients[12 * e], a, b, m.restVolume[e], m.lambda, m.mu,
                               stiffnessScale, block);
  };
  kernels::gatherElementRow(i, 4, m.rowStart, m.incidence, m.scatter, elementForce, addBlock, values, force);
}

}  // namespace

struct DeviceLinearTetAssembly::Impl {
  MeshArrays mesh{};
  int64_t blocks = 0;
  DeviceArray<int32_t> elementNodes, rowStart, incidenceStart, incidenceElement, scatter;
  DeviceArray<uint8_t> incidenceCorner;
  DeviceArray<double> restGradients, restVolume, positions, quat, elementForce, rotatedGrad, values, force;

  void assemble(double stiffnessScale) {
    corotateKernel<<<launch::blocks(mesh.elements), launch::kThreads>>>(mesh, positions.get(), quat.get(),
                                                                          elementForce.get(), rotatedGrad.get());
    gatherKernel<<<launch::blocks(mesh.nodes), launch::kThreads>>>(mesh, elementForce.get(), rotatedGrad.get(),
                                                                     stiffnessScale, values.get(), force.get());
  }
};

DeviceLinearTetAssembly::DeviceLinearTetAssembly(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceLinearTetAssembly::~DeviceLinearTetAssembly() = default;

std::unique_ptr<DeviceLinearTetAssembly> DeviceLinearTetAssembly::create(const LinearTetAssemblyView& view,
                                                                         std::string* error) {
  auto d = std::make_unique<Impl>();
  const size_t nodes = static_cast<size_t>(view.nodes), elements = static_cast<size_t>(view.elements);
  const size_t pairs = static_cast<size_t>(view.incidence.start[view.nodes]);
  d->blocks = view.rowStart[view.nodes];
  if (failed(d->elementNodes.upload(view.elementNodes, 4 * elements), error) ||
      failed(d->restGradients.upload(view.restGradients, 12 * elements), error) ||
      failed(d->restVolume.upload(view.restVolume, elements), error) ||
      failed(d->rowStart.upload(view.rowStart, nodes + 1), error) ||
      failed(d->incidenceStart.upload(view.incidence.start, nodes + 1), error) ||
      failed(d->incidenceElement.upload(view.incidence.element, pairs), error) ||
      failed(d->incidenceCorner.upload(view.incidence.corner, pairs), error) ||
      failed(d->scatter.upload(view.scatter, 16 * elements), error) || failed(d->positions.allocate(3 * nodes), error) ||
      failed(d->quat.allocate(4 * elements), error) || failed(d->elementForce.allocate(12 * elements), error) ||
      failed(d->rotatedGrad.allocate(12 * elements), error) ||
      failed(d->values.allocate(9 * static_cast<size_t>(d->blocks)), error) || failed(d->force.allocate(3 * nodes), error))
    return nullptr;
  d->mesh = MeshArrays{view.nodes,
                       view.elements,
                       d->elementNodes.get(),
                       d->restGradients.get(),
                       d->restVolume.get(),
                       view.lambda,
                       view.mu,
                       d->rowStart.get(),
                       {d->incidenceStart.get(), d->incidenceElement.get(), d->incidenceCorner.get()},
                       d->scatter.get()};
  return std::unique_ptr<DeviceLinearTetAssembly>(new DeviceLinearTetAssembly(std::move(d)));
}

bool DeviceLinearTetAssembly::assemble(const double* x, double* quat, double stiffnessScale, double* values,
                                       double* force, std::string* error) {
  Impl& d = *impl_;
  const size_t nodes = static_cast<size_t>(d.mesh.nodes), elements = static_cast<size_t>(d.mesh.elements);
  if (failed(cudaMemcpy(d.positions.get(), x, 3 * nodes * sizeof(double), cudaMemcpyHostToDevice), error) ||
      failed(cudaMemcpy(d.quat.get(), quat, 4 * elements * sizeof(double), cudaMemcpyHostToDevice), error))
    return false;
  d.assemble(stiffnessScale);
  return !failed(cudaMemcpy(quat, d.quat.get(), 4 * elements * sizeof(double), cudaMemcpyDeviceToHost), error) &&
         !failed(cudaMemcpy(values, d.values.get(), 9 * static_cast<size_t>(d.blocks) * sizeof(double),
                            cudaMemcpyDeviceToHost),
                 error) &&
         !failed(cudaMemcpy(force, d.force.get(), 3 * nodes * sizeof(double), cudaMemcpyDeviceToHost), error);
}

bool DeviceLinearTetAssembly::timeAssemble(int repeats, double stiffnessScale, double* msPerAssembly,
                                           std::string* error) {
  EventTimer timer;
  timer.start();
  for (int r = 0; r < repeats; ++r) impl_->assemble(stiffnessScale);
  const double ms = timer.stopMs();
  if (failed(cudaGetLastError(), error)) return false;
  *msPerAssembly = ms / (repeats > 0 ? repeats : 1);
  return true;
}

}  // namespace vp::gpu
