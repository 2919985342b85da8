// The issues' cantilever beam (tests/bench/beam_mesh.h, x = 0 clamped) as one implicit step's
// linear system, on the CPU and in the forms the device takes: the backward-Euler matrix of a
// 1/60 s step at rest, the step's gravity impulse as right-hand side, the clamped nodes
// filtered out. Shared by the gpu tests and the gpu benchmarks.
#pragma once

#include <memory>
#include <vector>

#include "beam_mesh.h"
#include "deform/deformable_body.h"
#include "deform/node_constraints.h"
#include "deform_beam_desc.h"
#include "gpu_kernels/device_block_system.h"
#include "linalg/bin_bcsr_matrix.h"
#include "linalg/conjugate_gradient.h"

namespace vp::gpu_test {

struct BeamStepSystem {
  std::unique_ptr<DeformableBody> body;
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  BinBcsrMatrix<double> bin;
  Array<double> inverseDiagonal;
  std::vector<double> rhs;
  NodeConstraints constraints;  // the clamped nodes fixed

  const BlockSparseMatrix<double>& matrix() const { return body->stepMatrix(); }
  int64_t dofs() const { return 3 * static_cast<int64_t>(matrix().blockRows); }

  gpu::HostBlockSystem host(bool withBcsr) const {
    gpu::HostBlockSystem h;
    h.matrix = bin.view();
    h.slots = bin.slots();
    h.inverseDiagonal = inverseDiagonal.data();
    h.nodeKind = constraints.kind.data();
    h.nodeNormal = constraints.normal.data();
    if (withBcsr) {
      h.bcsrRowStart = matrix().rowStart.data();
      h.bcsrColumns = matrix().columns.data();
      h.bcsrValues = matrix().values.data();
    }
    return h;
  }
};

// False (with the reason in lastError()) when the body cannot be made.
inline bool makeBeamStepSystem(const bench::BeamCells& cells, int degree, BeamStepSystem* out) {
  const bench::BeamMesh beam = bench::makeBeamMesh(cells.x, cells.y, cells.z, 4.0, 1.0, 1.0);
  DeformableDesc desc = bench::beamDeformableDesc(beam, degree);
  desc.solver.preconditioner = Preconditioner::BlockJacobi;  // the step only assembles the matrix
  desc.solver.maxIterations = 1;
  if (!ok(DeformableBody::create(std::move(desc), &out->body))) return false;
  DeformableBody& body = *out->body;
  body.setPinned(beam.fixedVertices.data(), static_cast<int64_t>(beam.fixedVertices.size()), true);
  DeformableStepInput in;
  in.dt = 1.0 / 60.0;
  in.tasks = out->tasks.get();
  ActorStats stats;
  body.step(in, &stats);  // at rest: the matrix of the rest configuration
  const int32_t n = body.nodeCount();
  out->rhs.assign(3 * static_cast<size_t>(n), 0.0);
  out->constraints.resize(n);
  for (int32_t i = 0; i < n; ++i) {
    if (body.pinned(i)) out->constraints.kind[i] = NodeConstraints::kFixed;
    else out->rhs[3 * i + 1] = -in.dt * body.nodeMasses()[i] * 9.81;
  }
  buildBinBcsr(out->matrix(), &out->bin);
  binnedInverseDiagonal(out->matrix(), &out->inverseDiagonal);
  return true;
}

// The system as the CPU's CG takes it (block-Jacobi, the constraints' filter).
inline LinearSystem cpuLinearSystem(const BeamStepSystem& sys) {
  LinearSystem system;
  system.size = sys.dofs();
  system.apply = [&sys](const double* x, double* y) { sys.matrix().multiply(*sys.tasks, x, y); };
  system.precondition = [&sys](const double* r, double* z) {
    for (int32_t row = 0; row < sys.matrix().blockRows; ++row)
      kernels::blockJacobiRow(row, sys.inverseDiagonal.data(), r, z);
  };
  system.filter = [&sys](double* v) { sys.constraints.filter(*sys.tasks, v); };
  return system;
}

}  // namespace vp::gpu_test
