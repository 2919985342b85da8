// The divergence guard's energy test for one step of an actor (every actor kind restores its
// last good state when it blows up). A step's mechanical energy (kinetic plus stored: a
// deformable's corotated elastic energy) may change by the work done on the actor and no more:
// the damping, friction and integrators only take energy out. Some work is known exactly
// (gravity, the host's forces, a deformable's constraint impulses), some only by a bound on its
// magnitude (a moving collider's contacts with a rigid body, the solver's penetration recovery,
// a fluid's sources and moving boundaries): the bound counts both as explained and as energy
// the step had to work with. A step whose energy rises beyond its work by more than
// kGrowthFactor times the energy it had to work with has blown up, even while every speed is
// finite and below the speed guard's bound.
#pragma once

namespace vp {

struct StepEnergy {
  double kineticStart = 0.0, elasticStart = 0.0;
  double kineticEnd = 0.0, elasticEnd = 0.0;
  double gravityWork = 0.0;  // Σ m g · (x' − x)
  double appliedWork = 0.0;  // host forces, friction and constraint impulses, each · (x' − x) or · v'
  double boundedWork = 0.0;  // ≥ 0: the most the work known only by a bound can put in
};

class StepEnergyGuard {
 public:
  // The unexplained gain may be this many times the energy the step had to work with (its
  // start energy and the magnitudes of the works): an energy that at least doubles unasked.
  static constexpr double kGrowthFactor = 1.0;
  // Gains below the kinetic energy of the whole actor at this speed (m/s) are rounding.
  static constexpr double kNoiseSpeed = 1e-3;

  // The energy rise the step's work does not explain (J; negative: dissipated).
  static double unexplainedGain(const StepEnergy& e);
  // The energy the step had to work with (J): start energy and the works' magnitudes.
  static double available(const StepEnergy& e);
  static bool blewUp(const StepEnergy& e, double totalMass);
};

}  // namespace vp
