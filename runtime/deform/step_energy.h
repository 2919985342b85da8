// The divergence guard's energy test for one implicit step of a deformable (issue: every actor
// restores its last good state when it blows up). Backward Euler with Rayleigh damping only
// loses mechanical energy: over a step the kinetic plus elastic energy changes by the work of
// gravity, the host's forces, sliding friction and the constraint impulses (pins, attachments
// and contacts: J = A v' − b at their nodes, which is how moving colliders and attachment
// targets put energy in), less what damping and the integrator dissipate. A step whose energy
// rises beyond that work by more than kGrowthFactor times the energy it had to work with has
// blown up, even while every speed is finite and below the speed guard's bound.
#pragma once

namespace vp {

struct StepEnergy {
  double kineticStart = 0.0, elasticStart = 0.0;
  double kineticEnd = 0.0, elasticEnd = 0.0;
  double gravityWork = 0.0;  // Σ m g · (x' − x)
  double appliedWork = 0.0;  // host forces, friction and constraint impulses, each · (x' − x) or · v'
};

class StepEnergyGuard {
 public:
  // The unexplained gain may be this many times the energy the step had to work with (its
  // start energy and the magnitudes of the works): an energy that at least doubles unasked.
  static constexpr double kGrowthFactor = 1.0;
  // Gains below the kinetic energy of the whole body at this speed (m/s) are rounding.
  static constexpr double kNoiseSpeed = 1e-3;

  // The energy rise the step's work does not explain (J; negative: dissipated).
  static double unexplainedGain(const StepEnergy& e);
  static bool blewUp(const StepEnergy& e, double totalMass);
};

}  // namespace vp
