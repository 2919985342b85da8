// Built with --fmad=false (gpu_kernels/CMakeLists.txt): the corotation and the blocks are the CPU's bits.
#include <cuda_runtime.h>

#include <string>
#include <utility>

#include "device_support.cuh"
#include "gpu_kernels/device_element_assembly.h"
#include "gpu_kernels/linear_tet_kernels.h"

namespace vp::gpu {
namespace {

// The mesh as device pointers (the layout of ElementAssemblyView).
struct MeshArrays {
  int degree;
  int nodesPerElement;
  int32_t nodes;
  int64_t elements;
  const int32_t* elementNodes;
  const double* restGradients;
  const double* restVolume;
  double lambda, mu;
  const int32_t* rowStart;
  kernels::ElementIncidenceView incidence;
  const int32_t* scatter;
  const double* restPositions;
  const uint8_t* nodeCorners;
  kernels::BBStiffnessTermsView terms;
  kernels::BBStiffnessStructureView structure;
};

// The element's node positions (and, with rest != null, rest positions) from the node arrays.
__device__ void gatherCorners(const MeshArrays& m, int64_t e, const double* positions, double* x, double* rest) {
  const int N = m.nodesPerElement;
  for (int a = 0; a < N; ++a) {
    const int32_t node = m.elementNodes[N * e + a];
    for (int i = 0; i < 3; ++i) {
      x[3 * a + i] = positions[3 * node + i];
      if (rest) rest[3 * a + i] = m.restPositions[3 * node + i];
    }
  }
}

__global__ void __launch_bounds__(launch::kThreads)
    corotateLinearKernel(MeshArrays m, const double* positions, double* quat, double* elementForce,
                         double* rotatedGrad) {
  const int64_t e = launch::index();
  if (e >= m.elements) return;
  double x[12];
  gatherCorners(m, e, positions, x, nullptr);
  kernels::corotateLinearTet(x, &m.restGradients[12 * e], m.restVolume[e], m.lambda, m.mu, &quat[4 * e],
                             &elementForce[12 * e], &rotatedGrad[12 * e]);
}

__global__ void __launch_bounds__(launch::kThreads)
    corotateBBKernel(MeshArrays m, const double* positions, double stiffnessScale, double* quat, double* elementForce,
                     double* pairs) {
  const int64_t e = launch::index();
  if (e >= m.elements) return;
  const int N = m.nodesPerElement;
  double x[3 * kernels::kMaxElementNodes], x0[3 * kernels::kMaxElementNodes];
  gatherCorners(m, e, positions, x, x0);
  kernels::corotateBBElement(m.degree, m.nodeCorners, m.structure, x, x0, &m.restGradients[12 * e], m.restVolume[e],
                             m.lambda, m.mu, stiffnessScale, &quat[4 * e], &elementForce[3 * N * e],
                             &pairs[144 * e]);
}

// A thread per node row; the blocks of degree 1 from the rotated gradients (the scale applied
// here), of higher degrees from the gradient pairs (the scale already in them).
__global__ void __launch_bounds__(launch::kThreads)
    gatherKernel(MeshArrays m, const double* elementForce, const double* elementTerms, double stiffnessScale,
                 double* values, double* force) {
  const int64_t i = launch::index();
  if (i >= m.nodes) return;
  const int N = m.nodesPerElement;
  if (m.degree == 1) {
    const auto addBlock = [&](int64_t e, int a, int b, double* block) {
      kernels::addLinearTetBlock(&elementTerms[12 * e], &m.restGradients[12 * e], a, b, m.restVolume[e], m.lambda,
                                 m.mu, stiffnessScale, block);
    };
    kernels::gatherElementRow(i, N, m.rowStart, m.incidence, m.scatter, elementForce, addBlock, values, force);
    return;
  }
  const auto addBlock = [&](int64_t e, int a, int b, double* block) {
    kernels::addBBRotatedBlock(m.terms, &elementTerms[144 * e], N, a, b, block);
  };
  kernels::gatherElementRow(i, N, m.rowStart, m.incidence, m.scatter, elementForce, addBlock, values, force);
}

}  // namespace

struct DeviceElementAssembly::Impl {
  MeshArrays mesh{};
  int64_t blocks = 0;
  DeviceArray<int32_t> elementNodes, rowStart, incidenceStart, incidenceElement, scatter, termStart;
  DeviceArray<uint8_t> incidenceCorner, nodeCorners, termPair;
  DeviceArray<int8_t> raised, lowered;
  DeviceArray<double> restGradients, restVolume, restPositions, termWeight, gram;
  // Per step: positions, rotations, element forces, the elements' rotated gradients (degree 1)
  // or gradient pairs, the block values and the node forces.
  DeviceArray<double> positions, quat, elementForce, elementTerms, values, force;

  void assemble(double stiffnessScale) {
    const unsigned elementBlocks = launch::blocks(mesh.elements);
    if (mesh.degree == 1) {
      corotateLinearKernel<<<elementBlocks, launch::kThreads>>>(mesh, positions.get(), quat.get(), elementForce.get(),
                                                                 elementTerms.get());
    } else {
      corotateBBKernel<<<elementBlocks, launch::kThreads>>>(mesh, positions.get(), stiffnessScale, quat.get(),
                                                             elementForce.get(), elementTerms.get());
    }
    gatherKernel<<<launch::blocks(mesh.nodes), launch::kThreads>>>(mesh, elementForce.get(), elementTerms.get(),
                                                                     stiffnessScale, values.get(), force.get());
  }
};

DeviceElementAssembly::DeviceElementAssembly(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceElementAssembly::~DeviceElementAssembly() = default;

std::unique_ptr<DeviceElementAssembly> DeviceElementAssembly::create(const ElementAssemblyView& view,
                                                                     std::string* error) {
  if (view.degree < 1 || view.degree > 3) {
    if (error) *error = "ElementAssemblyView.degree must be 1, 2 or 3, got " + std::to_string(view.degree);
    return nullptr;
  }
  auto d = std::make_unique<Impl>();
  const int N = kernels::elementNodeCount(view.degree);
  const size_t nodes = static_cast<size_t>(view.nodes), elements = static_cast<size_t>(view.elements);
  const size_t pairs = static_cast<size_t>(view.incidence.start[view.nodes]);
  d->blocks = view.rowStart[view.nodes];
  const size_t termsPerElement = view.degree == 1 ? 12 : 144;
  if (failed(d->elementNodes.upload(view.elementNodes, N * elements), error) ||
      failed(d->restGradients.upload(view.restGradients, 12 * elements), error) ||
      failed(d->restVolume.upload(view.restVolume, elements), error) ||
      failed(d->rowStart.upload(view.rowStart, nodes + 1), error) ||
      failed(d->incidenceStart.upload(view.incidence.start, nodes + 1), error) ||
      failed(d->incidenceElement.upload(view.incidence.element, pairs), error) ||
      failed(d->incidenceCorner.upload(view.incidence.corner, pairs), error) ||
      failed(d->scatter.upload(view.scatter, static_cast<size_t>(N) * N * elements), error) ||
      failed(d->positions.allocate(3 * nodes), error) || failed(d->quat.allocate(4 * elements), error) ||
      failed(d->elementForce.allocate(3 * N * elements), error) ||
      failed(d->elementTerms.allocate(termsPerElement * elements), error) ||
      failed(d->values.allocate(9 * static_cast<size_t>(d->blocks)), error) || failed(d->force.allocate(3 * nodes), error))
    return nullptr;
  if (view.degree > 1) {
    const size_t terms = static_cast<size_t>(view.terms.start[N * N]);
    const int lower = view.structure.lowerCount;
    if (failed(d->restPositions.upload(view.restPositions, 3 * nodes), error) ||
        failed(d->nodeCorners.upload(view.nodeCorners, N), error) ||
        failed(d->termStart.upload(view.terms.start, static_cast<size_t>(N) * N + 1), error) ||
        failed(d->termPair.upload(view.terms.pair, terms), error) ||
        failed(d->termWeight.upload(view.terms.weight, terms), error) ||
        failed(d->gram.upload(view.structure.gram, static_cast<size_t>(lower) * lower), error) ||
        failed(d->raised.upload(view.structure.raised, 4 * static_cast<size_t>(lower)), error) ||
        failed(d->lowered.upload(view.structure.lowered, 4 * static_cast<size_t>(N)), error))
      return nullptr;
  }
  MeshArrays& m = d->mesh;
  m.degree = view.degree;
  m.nodesPerElement = N;
  m.nodes = view.nodes;
  m.elements = view.elements;
  m.elementNodes = d->elementNodes.get();
  m.restGradients = d->restGradients.get();
  m.restVolume = d->restVolume.get();
  m.lambda = view.lambda;
  m.mu = view.mu;
  m.rowStart = d->rowStart.get();
  m.incidence = {d->incidenceStart.get(), d->incidenceElement.get(), d->incidenceCorner.get()};
  m.scatter = d->scatter.get();
  m.restPositions = d->restPositions.get();
  m.nodeCorners = d->nodeCorners.get();
  m.terms = {d->termStart.get(), d->termPair.get(), d->termWeight.get()};
  m.structure = {view.structure.lowerCount, d->gram.get(), d->raised.get(), d->lowered.get()};
  return std::unique_ptr<DeviceElementAssembly>(new DeviceElementAssembly(std::move(d)));
}

bool DeviceElementAssembly::assemble(const double* x, double* quat, double stiffnessScale, double* values,
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

bool DeviceElementAssembly::timeAssemble(int repeats, double stiffnessScale, double* msPerAssembly,
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
