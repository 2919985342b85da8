// Fluid actors: creation from vpFluidDef, field and surface access, stats.
#include <cmath>

#include "capi_convert.h"
#include "capi_versioned_struct.h"
#include "capi_copy_out.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

namespace {

// Values are copied as they are (enums through their bits); validateFluidDesc is the one check.
void translateRegion(const vpFluidRegion& r, FluidShape* out) {
  out->type = static_cast<FluidShape::Type>(rawEnum(r.type));
  out->centre = toVec3(r.centre);
  out->halfExtents = toVec3(r.halfExtents);
  out->radius = r.radius;
}

// Arrays of sources: a count without an array is a host bug worth naming.
template <class T>
Status checkArray(const char* field, const char* countField, const T* items, int32_t count) {
  if (count < 0 || count > 4096) return fail(Status::InvalidArgument, "%s = %d: must be in [0, 4096]", countField, count);
  if (count > 0 && items == nullptr)
    return fail(Status::InvalidArgument, "%s is NULL with %s = %d", field, countField, count);
  return Status::Ok;
}

Status translateFluidDef(const vpFluidDef& d, FluidDesc* desc) {
  desc->kind = static_cast<FluidKind>(rawEnum(d.kind));
  desc->grid.origin = toVec3(d.origin);
  desc->grid.nx = d.resolution[0];
  desc->grid.ny = d.resolution[1];
  desc->grid.nz = d.resolution[2];
  desc->grid.h = d.cellSize;
  for (int s = 0; s < 6; ++s) desc->sides[s] = static_cast<DomainSide>(rawEnum(d.sides[s]));
  desc->density = d.density;
  desc->kinematicViscosity = d.kinematicViscosity;
  desc->solver.advection = static_cast<AdvectionScheme>(rawEnum(d.advection));
  desc->solver.cflNumber = d.cflNumber;
  desc->solver.maxSubsteps = d.maxSubsteps;
  desc->solver.pressureTolerance = d.pressureTolerance;
  desc->solver.pressureMaxIterations = d.pressureMaxIterations;
  desc->smoke.ambientTemperature = d.ambientTemperature;
  desc->smoke.densityBuoyancy = d.densityBuoyancy;
  desc->smoke.thermalBuoyancy = d.thermalBuoyancy;
  desc->smoke.vorticityConfinement = d.vorticityConfinement;
  desc->smoke.densityDissipation = d.densityDissipation;
  desc->smoke.temperatureDissipation = d.temperatureDissipation;
  VP_TRY(checkArray("initialLiquid", "initialLiquidCount", d.initialLiquid, d.initialLiquidCount));
  VP_TRY(checkArray("emitters", "emitterCount", d.emitters, d.emitterCount));
  VP_TRY(checkArray("drains", "drainCount", d.drains, d.drainCount));
  for (int32_t i = 0; i < d.initialLiquidCount; ++i) {
    desc->initialLiquid.emplace_back();
    translateRegion(d.initialLiquid[i], &desc->initialLiquid.back());
  }
  for (int32_t i = 0; i < d.drainCount; ++i) {
    desc->drains.emplace_back();
    translateRegion(d.drains[i], &desc->drains.back());
  }
  for (int32_t i = 0; i < d.emitterCount; ++i) {
    const vpFluidEmitter& e = d.emitters[i];
    FluidEmitter out;
    translateRegion(e.region, &out.shape);
    out.velocity = toVec3(e.velocity);
    out.densityRate = e.densityRate;
    out.temperature = e.temperature;
    desc->emitters.push_back(out);
  }
  desc->twoWayCoupling = d.twoWayCoupling != 0;
  desc->priority = d.priority;
  desc->filter = toFilter(d.filter);
  desc->userData = d.userData;
  return Status::Ok;
}

}  // namespace

extern "C" {

int vpFluidIdIsNull(vpFluidId id) { return id.index1 == 0; }

vpFluidDef vpDefaultFluidDef(void) {
  const FluidDesc defaults;
  vpFluidDef d{};
  d.structSize = sizeof(vpFluidDef);
  d.kind = vpFluidKind_Smoke;
  d.resolution[0] = d.resolution[1] = d.resolution[2] = 32;
  d.cellSize = 1.0f / 32.0f;
  for (int s = 0; s < 6; ++s) d.sides[s] = vpDomainSide_Wall;
  d.density = static_cast<float>(defaults.density);
  d.kinematicViscosity = static_cast<float>(defaults.kinematicViscosity);
  d.advection = vpAdvection_MacCormack;
  d.cflNumber = static_cast<float>(defaults.solver.cflNumber);
  d.maxSubsteps = defaults.solver.maxSubsteps;
  d.pressureTolerance = static_cast<float>(defaults.solver.pressureTolerance);
  d.pressureMaxIterations = defaults.solver.pressureMaxIterations;
  d.ambientTemperature = static_cast<float>(defaults.smoke.ambientTemperature);
  d.densityBuoyancy = static_cast<float>(defaults.smoke.densityBuoyancy);
  d.thermalBuoyancy = static_cast<float>(defaults.smoke.thermalBuoyancy);
  d.vorticityConfinement = static_cast<float>(defaults.smoke.vorticityConfinement);
  d.densityDissipation = static_cast<float>(defaults.smoke.densityDissipation);
  d.temperatureDissipation = static_cast<float>(defaults.smoke.temperatureDissipation);
  d.twoWayCoupling = defaults.twoWayCoupling ? 1 : 0;
  d.priority = defaults.priority;
  d.filter = toC(defaults.filter);
  return d;
}

vpStatus vpFluidCreate(vpWorldId worldId, const vpFluidDef* def, vpFluidId* out) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(def);
    VP_REQUIRE_POINTER(out);
    WorldLease world;
    VP_TRY(resolveWorld(worldId, &world));
    vpFluidDef d;  // the host's def, with an older header's missing fields at their defaults
    VP_TRY(readVersioned("vpFluidDef", def, vpDefaultFluidDef(), &d));
    FluidDesc desc;
    VP_TRY(translateFluidDef(d, &desc));
    FluidHandle h;
    VP_TRY(world->createFluid(std::move(desc), &h));
    *out = makeFluidId(worldId, h);
    return Status::Ok;
  });
}

vpStatus vpFluidDestroy(vpFluidId id) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    return w->destroyFluid(handleOf(id));
  });
}

vpStatus vpFluidIsValid(vpFluidId id) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    return resolveFluid(id, &w, &f);
  });
}

vpStatus vpFluidGetResolution(vpFluidId id, int32_t* outNx, int32_t* outNy, int32_t* outNz) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    const MacGridSpec& s = f->grid().spec;
    if (outNx) *outNx = s.nx;
    if (outNy) *outNy = s.ny;
    if (outNz) *outNz = s.nz;
    return Status::Ok;
  });
}

vpStatus vpFluidGetKind(vpFluidId id, vpFluidKind* outKind) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    if (outKind) *outKind = f->desc().kind == FluidKind::Liquid ? vpFluidKind_Liquid : vpFluidKind_Smoke;
    return Status::Ok;
  });
}

vpStatus vpFluidGetDomain(vpFluidId id, vpVec3* outOrigin, float* outCellSize) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    const MacGridSpec& s = f->grid().spec;
    if (outOrigin) *outOrigin = toC(s.origin);
    if (outCellSize) *outCellSize = static_cast<float>(s.h);
    return Status::Ok;
  });
}

vpStatus vpFluidGetField(vpFluidId id, vpFluidField field, float* outValues, int64_t capacity) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outValues);
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    const int which = rawEnum(field);
    const Array<double>* values = which == vpFluidField_SmokeDensity ? &f->smokeDensity()
                                      : which == vpFluidField_Temperature  ? &f->temperature()
                                      : which == vpFluidField_LevelSet     ? &f->levelSet()
                                      : which == vpFluidField_Pressure     ? &f->pressure()
                                                                           : nullptr;
    if (values == nullptr) return fail(Status::InvalidArgument, "field = %d: not a vpFluidField", which);
    const int64_t cells = f->grid().cellCount();
    if (capacity < cells)
      return fail(Status::InvalidArgument, "capacity = %lld: the fluid has %lld cells", static_cast<long long>(capacity),
                  static_cast<long long>(cells));
    // Fields a kind does not have (and the pressure before the first step) read as zeros.
    for (int64_t c = 0; c < cells; ++c)
      outValues[c] = static_cast<size_t>(c) < values->size() ? static_cast<float>((*values)[static_cast<size_t>(c)]) : 0.0f;
    return Status::Ok;
  });
}

vpStatus vpFluidGetVelocityGrid(vpFluidId id, float* outXyz, int64_t capacity) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outXyz);
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    const MacGrid& g = f->grid();
    if (capacity < g.cellCount())
      return fail(Status::InvalidArgument, "capacity = %lld: the fluid has %lld cells", static_cast<long long>(capacity),
                  static_cast<long long>(g.cellCount()));
    for (int k = 0; k < g.spec.nz; ++k)
      for (int j = 0; j < g.spec.ny; ++j)
        for (int i = 0; i < g.spec.nx; ++i) {
          const size_t c = g.cellIndex(i, j, k);
          const Eigen::Vector3d u = g.cellVelocity(i, j, k);
          for (int a = 0; a < 3; ++a) outXyz[3 * c + a] = static_cast<float>(u[a]);
        }
    return Status::Ok;
  });
}

vpStatus vpFluidSampleVelocity(vpFluidId id, const vpVec3* points, int32_t count, vpVec3* outVelocities) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    if (count < 0) return fail(Status::InvalidArgument, "count = %d: must be >= 0", count);
    if (count > 0) {
      VP_REQUIRE_POINTER(points);
      VP_REQUIRE_POINTER(outVelocities);
    }
    for (int32_t i = 0; i < count; ++i) {
      VP_TRY(checkVec3(("points[" + std::to_string(i) + "]").c_str(), points[i]));
    }
    for (int32_t i = 0; i < count; ++i) outVelocities[i] = toC(f->sampleVelocity(toVec3(points[i])));
    return Status::Ok;
  });
}

vpStatus vpFluidGetSurfaceMeshSize(vpFluidId id, int32_t* outVertexCount, int32_t* outTriangleCount) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    const FluidSurface* surface = nullptr;
    VP_TRY(f->surface(&surface));
    const FluidSurface& s = *surface;
    if (outVertexCount) *outVertexCount = static_cast<int32_t>(s.positions.size());
    if (outTriangleCount) *outTriangleCount = static_cast<int32_t>(s.triangles.size());
    return Status::Ok;
  });
}

vpStatus vpFluidGetSurfaceMesh(vpFluidId id, float* outPositions, float* outNormals, int32_t vertexCapacity,
                               int32_t* outTriangles, int32_t triangleCapacity) {
  return guarded(__func__, [&] {
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    const FluidSurface* surface = nullptr;
    VP_TRY(f->surface(&surface));
    const FluidSurface& s = *surface;
    const int32_t nv = static_cast<int32_t>(s.positions.size()), nt = static_cast<int32_t>(s.triangles.size());
    if ((outPositions || outNormals) && vertexCapacity < nv)
      return fail(Status::InvalidArgument, "vertexCapacity = %d: the surface has %d vertices", vertexCapacity, nv);
    if (outTriangles && triangleCapacity < nt)
      return fail(Status::InvalidArgument, "triangleCapacity = %d: the surface has %d triangles", triangleCapacity, nt);
    for (int32_t i = 0; i < nv; ++i)
      for (int k = 0; k < 3; ++k) {
        if (outPositions) outPositions[3 * i + k] = static_cast<float>(s.positions[i][k]);
        if (outNormals) outNormals[3 * i + k] = static_cast<float>(s.normals[i][k]);
      }
    if (outTriangles)
      for (int32_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) outTriangles[3 * t + k] = s.triangles[t][k];
    return Status::Ok;
  });
}

vpStatus vpFluidGetAmount(vpFluidId id, float* outAmount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outAmount);
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    *outAmount = static_cast<float>(f->desc().kind == FluidKind::Liquid ? f->liquidVolume() : f->totalSmoke());
    return Status::Ok;
  });
}

vpStatus vpFluidGetStats(vpFluidId id, vpActorStats* outStats) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outStats);
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    vpActorStats stats = vpDefaultActorStats();
    stats.kind = vpActorKind_Fluid;
    stats.index1 = id.index1;
    for (const ActorStats& a : w->lastStats().actors)
      if (a.kind == ActorKind::Fluid && a.index1 == id.index1 && a.generation == handleOf(id).generation) fillActorStats(a, &stats);
    return writeVersioned("vpActorStats", stats, outStats);
  });
}

vpStatus vpWorldGetFluidCount(vpWorldId id, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    *outCount = static_cast<int32_t>(w->fluidCount());
    return Status::Ok;
  });
}

vpStatus vpWorldGetFluids(vpWorldId id, vpFluidId* outIds, int32_t capacity, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    return copyIdsOut(w->fluidHandles(), [&](FluidHandle h) { return makeFluidId(id, h); }, outIds, capacity,
                      outCount);
  });
}

vpStatus vpWorldFindFluid(vpWorldId id, const char* name, vpFluidId* out) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(name);
    VP_REQUIRE_POINTER(out);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    FluidHandle h;
    if (!w->findFluid(name, &h)) return fail(Status::InvalidArgument, "name = \"%s\": no fluid has this name", name);
    *out = makeFluidId(id, h);
    return Status::Ok;
  });
}

vpStatus vpFluidGetName(vpFluidId id, char* buffer, int32_t capacity, int32_t* outLength) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outLength);
    WorldLease w;
    FluidActor* f;
    VP_TRY(resolveFluid(id, &w, &f));
    return copyStringOut(f->desc().name, buffer, capacity, outLength);
  });
}

}  // extern "C"
