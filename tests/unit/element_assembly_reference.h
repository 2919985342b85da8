// A deformable's corotation and assembly written as plain loops over the kernel bodies
// (gpu_kernels/), the reference the device assembly's test compares with and that
// DeformAssemblyKernels.* holds to DeformableBody's own parallel assembly.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "gpu_kernels/bb_element_kernels.h"
#include "gpu_kernels/device_element_assembly.h"
#include "gpu_kernels/element_gather_kernels.h"
#include "gpu_kernels/linear_tet_kernels.h"

namespace vp::testref {

struct ElementAssembly {
  std::vector<double> quat, values, force;
};

// The two passes of a corotated assembly over the kernel bodies, one element and one node
// row at a time: quat (4 per element) is the rotations' warm start, scale the stiffness scale.
inline ElementAssembly elementAssembly(const gpu::ElementAssemblyView& m, const double* x, std::vector<double> quat,
                                       double scale) {
  const int N = kernels::elementNodeCount(m.degree);
  ElementAssembly out;
  out.quat = std::move(quat);
  std::vector<double> elementForce(3 * N * m.elements), terms((m.degree == 1 ? 12 : 144) * m.elements);
  for (int64_t e = 0; e < m.elements; ++e) {
    double corners[3 * kernels::kMaxElementNodes], rest[3 * kernels::kMaxElementNodes];
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < 3; ++i) {
        const int32_t node = m.elementNodes[N * e + a];
        corners[3 * a + i] = x[3 * node + i];
        rest[3 * a + i] = m.degree == 1 ? 0.0 : m.restPositions[3 * node + i];
      }
    if (m.degree == 1) {
      kernels::corotateLinearTet(corners, &m.restGradients[12 * e], m.restVolume[e], m.lambda, m.mu, &out.quat[4 * e],
                                 &elementForce[12 * e], &terms[12 * e]);
    } else {
      kernels::corotateBBElement(m.degree, m.nodeCorners, m.structure, corners, rest, &m.restGradients[12 * e],
                                 m.restVolume[e], m.lambda, m.mu, scale, &out.quat[4 * e], &elementForce[3 * N * e],
                                 &terms[144 * e]);
    }
  }
  out.values.resize(9 * static_cast<size_t>(m.rowStart[m.nodes]));
  out.force.resize(3 * static_cast<size_t>(m.nodes));
  const auto addBlock = [&](int64_t e, int a, int b, double* block) {
    if (m.degree == 1) {
      kernels::addLinearTetBlock(&terms[12 * e], &m.restGradients[12 * e], a, b, m.restVolume[e], m.lambda, m.mu,
                                 scale, block);
    } else {
      kernels::addBBRotatedBlock(m.terms, &terms[144 * e], N, a, b, block);
    }
  };
  for (int64_t i = 0; i < m.nodes; ++i)
    kernels::gatherElementRow(i, N, m.rowStart, m.incidence, m.scatter, elementForce.data(), addBlock,
                              out.values.data(), out.force.data());
  return out;
}

}  // namespace vp::testref
