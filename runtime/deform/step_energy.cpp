#include "deform/step_energy.h"

#include <cmath>

namespace vp {

double StepEnergyGuard::unexplainedGain(const StepEnergy& e) {
  return (e.kineticEnd + e.elasticEnd) - (e.kineticStart + e.elasticStart) - e.gravityWork - e.appliedWork;
}

bool StepEnergyGuard::blewUp(const StepEnergy& e, double totalMass) {
  const double available =
      e.kineticStart + e.elasticStart + std::abs(e.gravityWork) + std::abs(e.appliedWork);
  const double noise = 0.5 * totalMass * kNoiseSpeed * kNoiseSpeed;
  const double gain = unexplainedGain(e);
  return !std::isfinite(gain) || gain > kGrowthFactor * available + noise;
}

}  // namespace vp
