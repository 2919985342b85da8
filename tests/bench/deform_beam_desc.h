// The issues' beam as a deformable: the shared mesh (beam_mesh.h) with E = 1e8 Pa, ν = 0.3,
// ρ = 1000 kg/m³ (solver settings left to the caller).
#pragma once

#include "beam_mesh.h"
#include "deform/deformable_desc.h"

namespace vp::bench {

inline DeformableDesc beamDeformableDesc(const BeamMesh& beam, int degree) {
  DeformableDesc desc;
  desc.degree = degree;
  desc.mesh = toTetMesh(beam);
  desc.material.youngsModulus = 1e8;
  desc.material.poissonRatio = 0.3;
  desc.material.density = 1000.0;
  return desc;
}

}  // namespace vp::bench
