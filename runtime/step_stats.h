// What one world step reports: per actor, per phase timings, solver iterations, residuals
// and whether the budget cut a phase short. Mirrors vpStepStats/vpActorStats.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace vp {

enum class Phase : int {
  Rigid = 0, Corotate, Assemble, Contacts, Solve, Embed, Advect, Forces, Fractions, Pressure, Surface, Viscosity, Count
};
constexpr int kPhaseCount = static_cast<int>(Phase::Count);

enum class ActorKind : int { Rigid = 0, Deformable = 1, Fluid = 2 };

struct PhaseStats {
  double ms = 0.0;
  int iterations = 0;
  double residual = 0.0;
  bool budgetCut = false;
};

struct ActorStats {
  ActorKind kind = ActorKind::Rigid;
  uint32_t index1 = 0;
  uint32_t generation = 0;
  double totalMs = 0.0;
  bool diverged = false;  // the step blew up and the actor was restored to its previous state
  // Seconds this step advanced the actor: the frame's dt, 0 for a fluid the budget's pacing
  // deferred, several frames' dt for one that catches up (fluid_pacing.h).
  double simulatedDt = 0.0;
  std::array<PhaseStats, kPhaseCount> phases{};

  PhaseStats& phase(Phase p) { return phases[static_cast<int>(p)]; }
  const PhaseStats& phase(Phase p) const { return phases[static_cast<int>(p)]; }
};

struct StepStats {
  uint64_t stepIndex = 0;
  double dt = 0.0;
  double totalMs = 0.0;
  double budgetMs = 0.0;
  bool budgetCut = false;
  int colliderCount = 0;
  int rigidSubsteps = 0;
  int fluidInterval = 1;  // frames per fluid step chosen by the pacing for the next frames
  std::vector<ActorStats> actors;  // [0] is the rigid pseudo-actor
};

}  // namespace vp
