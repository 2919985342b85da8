/* Prints the C compiler's size of every struct in volphys.h and the offset of every field,
 * one "name value" per line, for the C# binding test to compare with Marshal.SizeOf/OffsetOf. */
#include <stddef.h>
#include <stdio.h>

#include "volphys/volphys.h"

#define SIZE(T) printf(#T " %u\n", (unsigned)sizeof(T))
#define FIELD(T, f) printf(#T "." #f " %u\n", (unsigned)offsetof(T, f))

int main(void) {
  SIZE(vpVersion); FIELD(vpVersion, major); FIELD(vpVersion, minor); FIELD(vpVersion, patch);
  SIZE(vpVec3); FIELD(vpVec3, x); FIELD(vpVec3, y); FIELD(vpVec3, z);
  SIZE(vpQuat); FIELD(vpQuat, x); FIELD(vpQuat, y); FIELD(vpQuat, z); FIELD(vpQuat, w);
  SIZE(vpTransform); FIELD(vpTransform, position); FIELD(vpTransform, rotation);
  SIZE(vpWorldId); FIELD(vpWorldId, index1); FIELD(vpWorldId, generation);
  SIZE(vpColliderId); FIELD(vpColliderId, index1); FIELD(vpColliderId, generation); FIELD(vpColliderId, world);
  SIZE(vpDeformableId); FIELD(vpDeformableId, index1); FIELD(vpDeformableId, generation);
  FIELD(vpDeformableId, world);
  SIZE(vpWorldDef); FIELD(vpWorldDef, structSize); FIELD(vpWorldDef, gravity); FIELD(vpWorldDef, workerCount);
  FIELD(vpWorldDef, frameBudgetMs); FIELD(vpWorldDef, rigidMaxSubstep); FIELD(vpWorldDef, enqueueTask);
  FIELD(vpWorldDef, finishTask); FIELD(vpWorldDef, userTaskContext); FIELD(vpWorldDef, clock);
  FIELD(vpWorldDef, clockContext); FIELD(vpWorldDef, userData); FIELD(vpWorldDef, device);
  SIZE(vpPhaseStats); FIELD(vpPhaseStats, ms); FIELD(vpPhaseStats, iterations); FIELD(vpPhaseStats, residual);
  FIELD(vpPhaseStats, budgetCut);
  SIZE(vpActorStats); FIELD(vpActorStats, structSize); FIELD(vpActorStats, kind); FIELD(vpActorStats, index1); FIELD(vpActorStats, totalMs);
  FIELD(vpActorStats, diverged); FIELD(vpActorStats, phases); FIELD(vpActorStats, simulatedDt);
  FIELD(vpActorStats, interval); FIELD(vpActorStats, completedStep); FIELD(vpActorStats, progress);
  FIELD(vpActorStats, slices); FIELD(vpActorStats, residual); FIELD(vpActorStats, priority);
  FIELD(vpActorStats, floorMissed); FIELD(vpActorStats, failedPhases); FIELD(vpActorStats, device);
  SIZE(vpStepStats); FIELD(vpStepStats, structSize); FIELD(vpStepStats, stepIndex); FIELD(vpStepStats, dt);
  FIELD(vpStepStats, totalMs); FIELD(vpStepStats, budgetMs); FIELD(vpStepStats, budgetCut);
  FIELD(vpStepStats, actorCount); FIELD(vpStepStats, colliderCount); FIELD(vpStepStats, rigidSubsteps);
  FIELD(vpStepStats, fluidInterval); FIELD(vpStepStats, overBudgetMs); FIELD(vpStepStats, budgetInfeasible);
  FIELD(vpStepStats, maxSliceMs);
  SIZE(vpShapeDef); FIELD(vpShapeDef, structSize); FIELD(vpShapeDef, type); FIELD(vpShapeDef, radius);
  FIELD(vpShapeDef, halfHeight); FIELD(vpShapeDef, halfExtents); FIELD(vpShapeDef, normal); FIELD(vpShapeDef, offset);
  FIELD(vpShapeDef, points); FIELD(vpShapeDef, pointCount); FIELD(vpShapeDef, indices);
  FIELD(vpShapeDef, triangleCount); FIELD(vpShapeDef, meshFile); FIELD(vpShapeDef, meshScale);
  SIZE(vpColliderDef); FIELD(vpColliderDef, structSize); FIELD(vpColliderDef, bodyType); FIELD(vpColliderDef, shape);
  FIELD(vpColliderDef, pose); FIELD(vpColliderDef, linearVelocity); FIELD(vpColliderDef, angularVelocity);
  FIELD(vpColliderDef, mass); FIELD(vpColliderDef, friction); FIELD(vpColliderDef, restitution);
  FIELD(vpColliderDef, linearDamping); FIELD(vpColliderDef, angularDamping); FIELD(vpColliderDef, userData);
  FIELD(vpColliderDef, filter);
  SIZE(vpCollisionFilter); FIELD(vpCollisionFilter, categoryBits); FIELD(vpCollisionFilter, maskBits);
  SIZE(vpQueryFilter); FIELD(vpQueryFilter, kinds); FIELD(vpQueryFilter, filter);
  SIZE(vpRay); FIELD(vpRay, origin); FIELD(vpRay, direction); FIELD(vpRay, maxDistance);
  SIZE(vpQueryHit); FIELD(vpQueryHit, kind); FIELD(vpQueryHit, collider); FIELD(vpQueryHit, deformable);
  FIELD(vpQueryHit, fluid); FIELD(vpQueryHit, distance); FIELD(vpQueryHit, point); FIELD(vpQueryHit, normal);
  FIELD(vpQueryHit, triangle); FIELD(vpQueryHit, barycentric); FIELD(vpQueryHit, nearestNode);
  SIZE(vpDeformableMaterial); FIELD(vpDeformableMaterial, structSize); FIELD(vpDeformableMaterial, youngsModulus);
  FIELD(vpDeformableMaterial, poissonRatio); FIELD(vpDeformableMaterial, density);
  FIELD(vpDeformableMaterial, massDamping); FIELD(vpDeformableMaterial, stiffnessDamping);
  FIELD(vpDeformableMaterial, friction);
  SIZE(vpFluidParameters); FIELD(vpFluidParameters, structSize); FIELD(vpFluidParameters, ambientTemperature);
  FIELD(vpFluidParameters, densityBuoyancy); FIELD(vpFluidParameters, thermalBuoyancy);
  FIELD(vpFluidParameters, vorticityConfinement); FIELD(vpFluidParameters, densityDissipation);
  FIELD(vpFluidParameters, temperatureDissipation); FIELD(vpFluidParameters, kinematicViscosity);
  FIELD(vpFluidParameters, sides);
  SIZE(vpContactEvent); FIELD(vpContactEvent, type); FIELD(vpContactEvent, deformable);
  FIELD(vpContactEvent, collider); FIELD(vpContactEvent, nodeCount); FIELD(vpContactEvent, point);
  FIELD(vpContactEvent, normal);
  SIZE(vpBodyProperties); FIELD(vpBodyProperties, structSize); FIELD(vpBodyProperties, mass);
  FIELD(vpBodyProperties, friction); FIELD(vpBodyProperties, restitution); FIELD(vpBodyProperties, linearDamping);
  FIELD(vpBodyProperties, angularDamping);
  SIZE(vpDeformableDef); FIELD(vpDeformableDef, structSize); FIELD(vpDeformableDef, degree);
  FIELD(vpDeformableDef, vertices); FIELD(vpDeformableDef, vertexCount); FIELD(vpDeformableDef, tets);
  FIELD(vpDeformableDef, tetCount); FIELD(vpDeformableDef, tetFile); FIELD(vpDeformableDef, surfaceFile);
  FIELD(vpDeformableDef, voxelResolution); FIELD(vpDeformableDef, renderVertices);
  FIELD(vpDeformableDef, renderVertexCount); FIELD(vpDeformableDef, renderTriangles);
  FIELD(vpDeformableDef, renderTriangleCount); FIELD(vpDeformableDef, pose); FIELD(vpDeformableDef, linearVelocity);
  FIELD(vpDeformableDef, youngsModulus); FIELD(vpDeformableDef, poissonRatio); FIELD(vpDeformableDef, density);
  FIELD(vpDeformableDef, massDamping); FIELD(vpDeformableDef, stiffnessDamping); FIELD(vpDeformableDef, friction);
  FIELD(vpDeformableDef, solverTolerance); FIELD(vpDeformableDef, solverMaxIterations);
  FIELD(vpDeformableDef, userData); FIELD(vpDeformableDef, targetResidual); FIELD(vpDeformableDef, priority);
  FIELD(vpDeformableDef, filter); FIELD(vpDeformableDef, surfaceMesher);
  FIELD(vpDeformableDef, selfCollision); FIELD(vpDeformableDef, meshGrading);
  SIZE(vpFluidId); FIELD(vpFluidId, index1); FIELD(vpFluidId, generation); FIELD(vpFluidId, world);
  SIZE(vpFluidRegion); FIELD(vpFluidRegion, type); FIELD(vpFluidRegion, centre); FIELD(vpFluidRegion, halfExtents);
  FIELD(vpFluidRegion, radius);
  SIZE(vpFluidEmitter); FIELD(vpFluidEmitter, region); FIELD(vpFluidEmitter, velocity);
  FIELD(vpFluidEmitter, densityRate); FIELD(vpFluidEmitter, temperature);
  SIZE(vpFluidDef); FIELD(vpFluidDef, structSize); FIELD(vpFluidDef, kind); FIELD(vpFluidDef, origin);
  FIELD(vpFluidDef, resolution); FIELD(vpFluidDef, cellSize); FIELD(vpFluidDef, sides); FIELD(vpFluidDef, density);
  FIELD(vpFluidDef, advection); FIELD(vpFluidDef, cflNumber); FIELD(vpFluidDef, maxSubsteps);
  FIELD(vpFluidDef, pressureTolerance); FIELD(vpFluidDef, pressureMaxIterations);
  FIELD(vpFluidDef, ambientTemperature); FIELD(vpFluidDef, densityBuoyancy); FIELD(vpFluidDef, thermalBuoyancy);
  FIELD(vpFluidDef, vorticityConfinement); FIELD(vpFluidDef, densityDissipation);
  FIELD(vpFluidDef, temperatureDissipation); FIELD(vpFluidDef, initialLiquid); FIELD(vpFluidDef, initialLiquidCount);
  FIELD(vpFluidDef, emitters); FIELD(vpFluidDef, emitterCount); FIELD(vpFluidDef, drains);
  FIELD(vpFluidDef, drainCount); FIELD(vpFluidDef, twoWayCoupling); FIELD(vpFluidDef, userData);
  FIELD(vpFluidDef, kinematicViscosity); FIELD(vpFluidDef, priority);
  FIELD(vpFluidDef, filter);
  SIZE(vpBuildInfo); FIELD(vpBuildInfo, cudaCompiled); FIELD(vpBuildInfo, cudaDeviceCount);
  FIELD(vpBuildInfo, hardwareThreads);
  SIZE(vpDeviceInfo); FIELD(vpDeviceInfo, structSize); FIELD(vpDeviceInfo, name); FIELD(vpDeviceInfo, totalMemoryBytes);
  FIELD(vpDeviceInfo, computeCapabilityMajor); FIELD(vpDeviceInfo, computeCapabilityMinor);
  FIELD(vpDeviceInfo, multiprocessorCount);
  return 0;
}
