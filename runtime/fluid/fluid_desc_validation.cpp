// Validation of FluidDesc (fluid_desc.h); messages name the vpFluidDef field and its value.
#include <cmath>

#include "actor_priority.h"
#include "core/physical_limits.h"
#include "fluid/fluid_desc.h"

namespace vp {
namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

Status checkRange(const char* field, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi))
    return fail(Status::InvalidArgument, "%s = %g: must be in [%g, %g]", field, value, lo, hi);
  return Status::Ok;
}

Status validateShape(const std::string& field, const FluidShape& s) {
  if (s.type != FluidShape::Type::Box && s.type != FluidShape::Type::Sphere)
    return fail(Status::InvalidArgument, "%s.type = %d: must be 0 (box) or 1 (sphere)", field.c_str(),
                static_cast<int>(s.type));
  if (!finite(s.centre))
    return fail(Status::InvalidArgument, "%s.centre = (%g, %g, %g): must be finite", field.c_str(), s.centre.x(),
                s.centre.y(), s.centre.z());
  if (s.type == FluidShape::Type::Box && !(finite(s.halfExtents) && (s.halfExtents.array() > 0.0).all()))
    return fail(Status::InvalidArgument, "%s.halfExtents = (%g, %g, %g): must be positive and finite",
                field.c_str(), s.halfExtents.x(), s.halfExtents.y(), s.halfExtents.z());
  if (s.type == FluidShape::Type::Sphere && !(s.radius > 0.0 && std::isfinite(s.radius)))
    return fail(Status::InvalidArgument, "%s.radius = %g: must be positive and finite", field.c_str(), s.radius);
  return Status::Ok;
}

}  // namespace

Status validateFluidDesc(const FluidDesc& d) {
  if (d.kind != FluidKind::Smoke && d.kind != FluidKind::Liquid)
    return fail(Status::InvalidArgument, "kind = %d: must be 0 (smoke) or 1 (liquid)", static_cast<int>(d.kind));
  const MacGridSpec& g = d.grid;
  VP_TRY(checkPosition("origin", g.origin));
  VP_TRY(checkLength("cellSize", g.h));
  const int counts[3] = {g.nx, g.ny, g.nz};
  const char* names[3] = {"resolution.x", "resolution.y", "resolution.z"};
  for (int a = 0; a < 3; ++a)
    if (counts[a] < 2 || counts[a] > kMaxFluidCellsPerAxis)
      return fail(Status::InvalidArgument, "%s = %d: must be in [2, %d]", names[a], counts[a], kMaxFluidCellsPerAxis);
  const int64_t cells = int64_t(g.nx) * g.ny * g.nz;
  if (cells > kMaxFluidCells)
    return fail(Status::InvalidArgument, "resolution = (%d, %d, %d): %lld cells, more than the %lld allowed", g.nx,
                g.ny, g.nz, static_cast<long long>(cells), static_cast<long long>(kMaxFluidCells));
  VP_TRY(checkDensity("density", d.density));
  VP_TRY(validateFluidControls(FluidControls{d.smoke, d.kinematicViscosity, d.emitters, d.sides}));
  const FluidSolverSettings& s = d.solver;
  if (s.advection != AdvectionScheme::SemiLagrangian && s.advection != AdvectionScheme::MacCormack)
    return fail(Status::InvalidArgument, "advection = %d: must be 0 (semi-Lagrangian) or 1 (MacCormack)",
                static_cast<int>(s.advection));
  VP_TRY(checkRange("cflNumber", s.cflNumber, 0.1, 100.0));
  if (s.maxSubsteps < 1 || s.maxSubsteps > 64)
    return fail(Status::InvalidArgument, "maxSubsteps = %d: must be in [1, 64]", s.maxSubsteps);
  VP_TRY(checkRange("pressureTolerance", s.pressureTolerance, 1e-14, 1.0));
  if (s.pressureMaxIterations < 1 || s.pressureMaxIterations > 100000)
    return fail(Status::InvalidArgument, "pressureMaxIterations = %d: must be in [1, 100000]",
                s.pressureMaxIterations);
  if (s.samplesPerSlice < 1)
    return fail(Status::InvalidArgument, "samplesPerSlice = %lld: must be >= 1",
                static_cast<long long>(s.samplesPerSlice));
  VP_TRY(validateActorPriority(d.priority));
  for (size_t i = 0; i < d.initialLiquid.size(); ++i)
    VP_TRY(validateShape("initialLiquid[" + std::to_string(i) + "]", d.initialLiquid[i]));
  for (size_t i = 0; i < d.drains.size(); ++i) VP_TRY(validateShape("drains[" + std::to_string(i) + "]", d.drains[i]));
  return Status::Ok;
}

Status validateFluidControls(const FluidControls& c) {
  for (int s = 0; s < 6; ++s)
    if (c.sides[s] != DomainSide::Wall && c.sides[s] != DomainSide::Open)
      return fail(Status::InvalidArgument, "sides[%d] = %d: must be 0 (wall) or 1 (open)", s,
                  static_cast<int>(c.sides[s]));
  VP_TRY(checkRange("kinematicViscosity", c.kinematicViscosity, 0.0, kMaxKinematicViscosity));
  const SmokeParameters& sp = c.smoke;
  VP_TRY(checkRange("ambientTemperature", sp.ambientTemperature, -1e6, 1e6));
  VP_TRY(checkRange("densityBuoyancy", sp.densityBuoyancy, -1e4, 1e4));
  VP_TRY(checkRange("thermalBuoyancy", sp.thermalBuoyancy, -1e4, 1e4));
  VP_TRY(checkRange("vorticityConfinement", sp.vorticityConfinement, 0.0, 100.0));
  VP_TRY(checkRange("densityDissipation", sp.densityDissipation, 0.0, 1e3));
  VP_TRY(checkRange("temperatureDissipation", sp.temperatureDissipation, 0.0, 1e3));
  for (size_t i = 0; i < c.emitters.size(); ++i) {
    const std::string field = "emitters[" + std::to_string(i) + "]";
    const FluidEmitter& e = c.emitters[i];
    VP_TRY(validateShape(field + ".region", e.shape));  // named as in vpFluidEmitter
    if (!finite(e.velocity) || e.velocity.norm() > 1e4)
      return fail(Status::InvalidArgument, "%s.velocity = (%g, %g, %g): must be finite, magnitude <= 1e4",
                  field.c_str(), e.velocity.x(), e.velocity.y(), e.velocity.z());
    VP_TRY(checkRange((field + ".densityRate").c_str(), e.densityRate, 0.0, 1e6));
    VP_TRY(checkRange((field + ".temperature").c_str(), e.temperature, -1e6, 1e6));
  }
  return Status::Ok;
}

}  // namespace vp
