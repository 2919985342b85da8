#include <cmath>

#include "actor_priority.h"
#include "core/physical_limits.h"
#include "deform/deformable_desc.h"
#include "geometry/tet_mesh_validation.h"

namespace vp {
namespace {

Status checkPositive(const char* field, double value, double maxValue) {
  if (!(value > 0.0 && value <= maxValue))
    return fail(Status::InvalidArgument, "%s = %g: must be in (0, %g]", field, value, maxValue);
  return Status::Ok;
}

Status checkNonNegative(const char* field, double value, double maxValue) {
  if (!(value >= 0.0 && value <= maxValue))
    return fail(Status::InvalidArgument, "%s = %g: must be in [0, %g]", field, value, maxValue);
  return Status::Ok;
}

}  // namespace

Status validateDeformableMaterial(const DeformableMaterial& m) {
  VP_TRY(checkPositive("youngsModulus", m.youngsModulus, 1e13));
  // ν = 0.5 makes λ infinite; stop just short of it (near-incompressible needs degree > 1).
  if (!(m.poissonRatio > -0.999 && m.poissonRatio < 0.4999))
    return fail(Status::InvalidArgument, "poissonRatio = %g: must be in (-0.999, 0.4999)", m.poissonRatio);
  VP_TRY(checkDensity("density", m.density));
  VP_TRY(checkNonNegative("massDamping", m.massDamping, 1e3));
  VP_TRY(checkNonNegative("stiffnessDamping", m.stiffnessDamping, 10.0));
  return checkNonNegative("friction", m.friction, 1e3);
}

Status validateDeformableDesc(DeformableDesc& in) {
  if (in.degree < 1 || in.degree > 3)
    return fail(Status::InvalidArgument, "degree = %d: must be 1, 2 or 3", in.degree);
  VP_TRY(validateDeformableMaterial(in.material));
  if (!(in.solver.tolerance > 0.0 && in.solver.tolerance < 1.0))
    return fail(Status::InvalidArgument, "solverTolerance = %g: must be in (0, 1)", in.solver.tolerance);
  // A floor below the solve's own tolerance could never be reached.
  const double target = in.solver.targetResidual;
  if (!(std::isfinite(target) && target <= 1.0))
    return fail(Status::InvalidArgument, "targetResidual = %g: must be finite and in [solverTolerance, 1]", target);
  if (target < in.solver.tolerance)
    return fail(Status::InvalidArgument, "targetResidual = %g: must be >= solverTolerance = %g", target,
                in.solver.tolerance);
  if (in.solver.maxIterations < 1 || in.solver.maxIterations > DeformableSolverSettings::kMaxSolverIterations)
    return fail(Status::InvalidArgument, "solverMaxIterations = %d: must be in [1, %d]", in.solver.maxIterations,
                DeformableSolverSettings::kMaxSolverIterations);
  VP_TRY(validateActorPriority(in.priority));
  const int self = static_cast<int>(in.selfCollision);
  if (self < static_cast<int>(SelfCollision::Auto) || self > static_cast<int>(SelfCollision::On))
    return fail(Status::InvalidArgument, "selfCollision = %d: must be vpSelfCollision_Auto (0), _Off (1) or _On (2)",
                self);
  VP_TRY(checkPose("pose", &in.pose));
  VP_TRY(checkLinearVelocity("linearVelocity", in.linearVelocity));
  if (in.renderMesh) {
    const SurfaceMesh& r = *in.renderMesh;
    const int32_t n = static_cast<int32_t>(r.vertices.size());
    for (size_t i = 0; i < r.vertices.size(); ++i)
      if (!r.vertices[i].allFinite()) return fail(Status::InvalidArgument, "renderVertices[%zu]: not finite", i);
    for (size_t t = 0; t < r.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        if (r.triangles[t][k] < 0 || r.triangles[t][k] >= n)
          return fail(Status::InvalidArgument, "renderTriangles[%zu] = %d: out of range [0, %d)", 3 * t + k,
                      r.triangles[t][k], n);
  }
  TetMesh mesh = in.mesh;  // the repair works on a copy so a failure leaves `in` unchanged
  Status s = validateAndRepairTetMesh(mesh, nullptr);
  if (!ok(s)) return addErrorContext(s, "mesh");
  in.mesh = std::move(mesh);
  in.pose.rotation.normalize();
  return Status::Ok;
}

}  // namespace vp
