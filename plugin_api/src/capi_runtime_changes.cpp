// Changes to actors after creation: a deformable's material, a fluid's forces,
// viscosity and emitters. Each is validated by the same rule as the def (the runtime's
// validateDeformableMaterial / validateFluidControls) and changes nothing on failure.
#include <vector>

#include "capi_convert.h"
#include "capi_versioned_struct.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

namespace {

vpDeformableMaterial toC(const DeformableMaterial& m) {
  vpDeformableMaterial out{};
  out.structSize = sizeof out;
  out.youngsModulus = static_cast<float>(m.youngsModulus);
  out.poissonRatio = static_cast<float>(m.poissonRatio);
  out.density = static_cast<float>(m.density);
  out.massDamping = static_cast<float>(m.massDamping);
  out.stiffnessDamping = static_cast<float>(m.stiffnessDamping);
  out.friction = static_cast<float>(m.friction);
  return out;
}

vpFluidParameters toC(const FluidControls& c) {
  vpFluidParameters out{};
  out.structSize = sizeof out;
  out.ambientTemperature = static_cast<float>(c.smoke.ambientTemperature);
  out.densityBuoyancy = static_cast<float>(c.smoke.densityBuoyancy);
  out.thermalBuoyancy = static_cast<float>(c.smoke.thermalBuoyancy);
  out.vorticityConfinement = static_cast<float>(c.smoke.vorticityConfinement);
  out.densityDissipation = static_cast<float>(c.smoke.densityDissipation);
  out.temperatureDissipation = static_cast<float>(c.smoke.temperatureDissipation);
  out.kinematicViscosity = static_cast<float>(c.kinematicViscosity);
  for (int s = 0; s < 6; ++s) out.sides[s] = static_cast<vpDomainSide>(c.sides[s]);
  return out;
}

}  // namespace

vpStatus vpDeformableGetMaterial(vpDeformableId id, vpDeformableMaterial* outMaterial) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outMaterial);
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    return writeVersioned("vpDeformableMaterial", toC(d->desc().material), outMaterial);
  });
}

vpStatus vpDeformableSetMaterial(vpDeformableId id, const vpDeformableMaterial* material) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(material);
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    vpDeformableMaterial m;  // an older header's missing fields keep their current values
    VP_TRY(readVersioned("vpDeformableMaterial", material, toC(d->desc().material), &m));
    DeformableMaterial next = d->desc().material;
    next.youngsModulus = m.youngsModulus;
    next.poissonRatio = m.poissonRatio;
    next.density = m.density;
    next.massDamping = m.massDamping;
    next.stiffnessDamping = m.stiffnessDamping;
    next.friction = m.friction;
    return d->setMaterial(next);
  });
}

vpStatus vpFluidGetParameters(vpFluidId id, vpFluidParameters* outParameters) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outParameters);
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    return writeVersioned("vpFluidParameters", toC(f->controls()), outParameters);
  });
}

vpStatus vpFluidSetParameters(vpFluidId id, const vpFluidParameters* parameters) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(parameters);
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    FluidControls next = f->controls();
    vpFluidParameters p;
    VP_TRY(readVersioned("vpFluidParameters", parameters, toC(next), &p));
    next.smoke.ambientTemperature = p.ambientTemperature;
    next.smoke.densityBuoyancy = p.densityBuoyancy;
    next.smoke.thermalBuoyancy = p.thermalBuoyancy;
    next.smoke.vorticityConfinement = p.vorticityConfinement;
    next.smoke.densityDissipation = p.densityDissipation;
    next.smoke.temperatureDissipation = p.temperatureDissipation;
    next.kinematicViscosity = p.kinematicViscosity;
    for (int s = 0; s < 6; ++s) next.sides[s] = static_cast<DomainSide>(rawEnum(p.sides[s]));
    return f->setControls(next);
  });
}

vpStatus vpFluidGetEmitterCount(vpFluidId id, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    *outCount = static_cast<int32_t>(f->controls().emitters.size());
    return Status::Ok;
  });
}

vpStatus vpFluidSetEmitter(vpFluidId id, int32_t index, int32_t enabled, float densityRate, vpVec3 velocity,
                           float temperature) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    FluidControls next = f->controls();
    if (index < 0 || index >= static_cast<int32_t>(next.emitters.size()))
      return fail(Status::InvalidArgument, "index = %d: the fluid has %zu emitters", index, next.emitters.size());
    FluidEmitter& e = next.emitters[static_cast<size_t>(index)];
    e.enabled = enabled != 0;
    e.densityRate = densityRate;
    e.velocity = toVec3(velocity);
    e.temperature = temperature;
    return f->setControls(next);
  });
}
