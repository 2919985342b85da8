#include "core/step_energy.h"

#include <cmath>

namespace vp {

double StepEnergyGuard::unexplainedGain(const StepEnergy& e) {
  return (e.kineticEnd + e.elasticEnd) - (e.kineticStart + e.elasticStart) - e.gravityWork - e.appliedWork -
         e.boundedWork;
}

double StepEnergyGuard::available(const StepEnergy& e) {
  return e.kineticStart + e.elasticStart + std::abs(e.gravityWork) + std::abs(e.appliedWork) + e.boundedWork;
}

bool StepEnergyGuard::blewUp(const StepEnergy& e, double totalMass) {
  const double noise = 0.5 * totalMass * kNoiseSpeed * kNoiseSpeed;
  const double gain = unexplainedGain(e);
  return !std::isfinite(gain) || gain > kGrowthFactor * available(e) + noise;
}

}  // namespace vp
