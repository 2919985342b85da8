// The C ABI's struct-size policy (volphys.h, "Versioned structs"). A struct with a structSize
// may come from an older header: structs only grow by appending fields, so an older struct is a
// prefix of this one that ends where one of this one's fields begins. Read (defs, properties
// set): the fields past structSize take their defaults. Written (stats, properties read): only
// the first structSize bytes are written. Larger than this library's struct (a newer header) or
// ending inside a field: VersionMismatch.
#pragma once

#include <array>
#include <cstddef>
#include <cstring>

#include "core/status.h"
#include "volphys/volphys.h"

namespace vp::capi {

// Where each field after structSize begins, in this library's layout: the sizes an older
// header's struct can have (with sizeof itself). One specialization per versioned struct.
template <class T>
struct FieldOffsets;

#define VP_OFFSETS(T, ...)                                  \
  template <>                                               \
  struct FieldOffsets<T> {                                  \
    using S = T;                                            \
    static constexpr std::array values{__VA_ARGS__};        \
  }
#define VP_AT(field) offsetof(S, field)

VP_OFFSETS(vpWorldDef, VP_AT(gravity), VP_AT(workerCount), VP_AT(frameBudgetMs), VP_AT(rigidMaxSubstep),
           VP_AT(enqueueTask), VP_AT(finishTask), VP_AT(userTaskContext), VP_AT(clock), VP_AT(clockContext),
           VP_AT(userData), VP_AT(device));
VP_OFFSETS(vpStepStats, VP_AT(stepIndex), VP_AT(dt), VP_AT(totalMs), VP_AT(budgetMs), VP_AT(budgetCut),
           VP_AT(actorCount), VP_AT(colliderCount), VP_AT(rigidSubsteps), VP_AT(fluidInterval),
           VP_AT(overBudgetMs), VP_AT(budgetInfeasible), VP_AT(maxSliceMs));
VP_OFFSETS(vpActorStats, VP_AT(kind), VP_AT(index1), VP_AT(totalMs), VP_AT(diverged), VP_AT(phases),
           VP_AT(simulatedDt), VP_AT(interval), VP_AT(completedStep), VP_AT(progress), VP_AT(slices),
           VP_AT(residual), VP_AT(priority), VP_AT(floorMissed), VP_AT(failedPhases), VP_AT(device));
VP_OFFSETS(vpDeviceInfo, VP_AT(name), VP_AT(totalMemoryBytes), VP_AT(computeCapabilityMajor),
           VP_AT(computeCapabilityMinor), VP_AT(multiprocessorCount));
VP_OFFSETS(vpShapeDef, VP_AT(type), VP_AT(radius), VP_AT(halfHeight), VP_AT(halfExtents), VP_AT(normal),
           VP_AT(offset), VP_AT(points), VP_AT(pointCount), VP_AT(indices), VP_AT(triangleCount), VP_AT(meshFile),
           VP_AT(meshScale));
VP_OFFSETS(vpColliderDef, VP_AT(bodyType), VP_AT(shape), VP_AT(pose), VP_AT(linearVelocity), VP_AT(angularVelocity),
           VP_AT(mass), VP_AT(friction), VP_AT(restitution), VP_AT(linearDamping), VP_AT(angularDamping),
           VP_AT(userData), VP_AT(filter));
VP_OFFSETS(vpBodyProperties, VP_AT(mass), VP_AT(friction), VP_AT(restitution), VP_AT(linearDamping),
           VP_AT(angularDamping));
VP_OFFSETS(vpDeformableMaterial, VP_AT(youngsModulus), VP_AT(poissonRatio), VP_AT(density), VP_AT(massDamping),
           VP_AT(stiffnessDamping), VP_AT(friction));
VP_OFFSETS(vpFluidParameters, VP_AT(ambientTemperature), VP_AT(densityBuoyancy), VP_AT(thermalBuoyancy),
           VP_AT(vorticityConfinement), VP_AT(densityDissipation), VP_AT(temperatureDissipation),
           VP_AT(kinematicViscosity));
VP_OFFSETS(vpDeformableDef, VP_AT(degree), VP_AT(vertices), VP_AT(vertexCount), VP_AT(tets), VP_AT(tetCount),
           VP_AT(tetFile), VP_AT(surfaceFile), VP_AT(voxelResolution), VP_AT(renderVertices),
           VP_AT(renderVertexCount), VP_AT(renderTriangles), VP_AT(renderTriangleCount), VP_AT(pose),
           VP_AT(linearVelocity), VP_AT(youngsModulus), VP_AT(poissonRatio), VP_AT(density), VP_AT(massDamping),
           VP_AT(stiffnessDamping), VP_AT(friction), VP_AT(solverTolerance), VP_AT(solverMaxIterations),
           VP_AT(userData), VP_AT(targetResidual), VP_AT(priority), VP_AT(filter), VP_AT(surfaceMesher),
           VP_AT(selfCollision), VP_AT(meshGrading));
VP_OFFSETS(vpFluidDef, VP_AT(kind), VP_AT(origin), VP_AT(resolution), VP_AT(cellSize), VP_AT(sides), VP_AT(density),
           VP_AT(advection), VP_AT(cflNumber), VP_AT(maxSubsteps), VP_AT(pressureTolerance),
           VP_AT(pressureMaxIterations), VP_AT(ambientTemperature), VP_AT(densityBuoyancy), VP_AT(thermalBuoyancy),
           VP_AT(vorticityConfinement), VP_AT(densityDissipation), VP_AT(temperatureDissipation),
           VP_AT(initialLiquid), VP_AT(initialLiquidCount), VP_AT(emitters), VP_AT(emitterCount), VP_AT(drains),
           VP_AT(drainCount), VP_AT(twoWayCoupling), VP_AT(userData), VP_AT(kinematicViscosity), VP_AT(priority),
           VP_AT(filter));

#undef VP_AT
#undef VP_OFFSETS

// VersionMismatch naming the struct unless `given` is sizeof(T) or one of its field offsets.
Status checkVersionedSize(const char* structName, uint32_t given, size_t size, const size_t* fieldOffsets,
                          size_t count);

template <class T>
Status checkStructSize(const char* structName, uint32_t given) {
  return checkVersionedSize(structName, given, sizeof(T), FieldOffsets<T>::values.data(),
                            FieldOffsets<T>::values.size());
}

// *out = `defaults` with the host's first structSize bytes over it; reads nothing past them.
template <class T>
Status readVersioned(const char* structName, const T* given, const T& defaults, T* out) {
  uint32_t size;
  std::memcpy(&size, given, sizeof size);
  VP_TRY(checkStructSize<T>(structName, size));
  *out = defaults;
  std::memcpy(static_cast<void*>(out), given, size);
  out->structSize = sizeof(T);
  return Status::Ok;
}

// Checks the host's structSize; writes only that many bytes of `value` (the host's own
// structSize stays as it was).
template <class T>
Status writeVersioned(const char* structName, const T& value, T* out) {
  uint32_t size;
  std::memcpy(&size, out, sizeof size);
  VP_TRY(checkStructSize<T>(structName, size));
  std::memcpy(static_cast<void*>(out), &value, size);
  std::memcpy(out, &size, sizeof size);
  return Status::Ok;
}

}  // namespace vp::capi
