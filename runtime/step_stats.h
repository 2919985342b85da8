// What one world step reports: per actor, per phase timings, solver iterations, residuals
// and whether the budget cut a phase short. Mirrors vpStepStats/vpActorStats, except
// ActorStats::substeps, which the C ABI does not carry yet.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace vp {

enum class Phase : int {
  Rigid = 0, Corotate, Assemble, Contacts, Solve, Embed, Advect, Forces, Fractions, Pressure, Surface, Viscosity,
  Coupling, Count
};
constexpr int kPhaseCount = static_cast<int>(Phase::Count);

enum class ActorKind : int { Rigid = 0, Deformable = 1, Fluid = 2 };

struct PhaseStats {
  double ms = 0.0;
  int iterations = 0;
  double residual = 0.0;
  bool budgetCut = false;
  bool failed = false;  // hit an error: the step went on without it (World::step says so)
};

struct ActorStats {
  ActorKind kind = ActorKind::Rigid;
  uint32_t index1 = 0;
  uint32_t generation = 0;
  double totalMs = 0.0;
  bool diverged = false;  // the step blew up and the actor was restored to its previous state
  // Seconds this step advanced the actor: the frame's dt, 0 for a fluid the budget's pacing
  // deferred, several frames' dt for one that catches up (frame_plan.h).
  double simulatedDt = 0.0;
  // Frames per step: a deformable steps every interval-th frame with interval * dt; a fluid's
  // last completed step spanned interval frames.
  int interval = 1;
  bool completedStep = false;  // a step of this actor completed in this frame
  int substeps = 0;            // fluid: the CFL sub-steps of the step that completed in this frame
  double progress = 0.0;       // fluid: fraction of its current step done at the frame's end; 1 when it completed
  int slices = 0;              // slices of this actor's work run in this frame
  double residual = 0.0;       // final relative residual of its iterative solve in this frame
  int priority = 0;            // its desc's priority: higher is served first when the budget is short
  bool floorMissed = false;    // deformable: the budget stopped its solve above its targetResidual
  bool onDevice = false;       // deformable: its implicit solve ran on the CUDA device
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
  int fluidInterval = 1;  // the largest interval among the fluids (ActorStats::interval)
  double overBudgetMs = 0.0;  // how far totalMs went past budgetMs; 0 when within it or unlimited
  // The actors' accuracy floors and minimum rates did not fit the budget: some actor ran at its
  // interval cap.
  bool budgetInfeasible = false;
  double maxSliceMs = 0.0;  // the longest single slice of work in this frame
  // Finding the deformables' contacts with each other and themselves (deform/pair_contacts.h).
  double deformableContactMs = 0.0;
  int deformablePairContacts = 0;  // how many it found
  std::vector<ActorStats> actors;  // [0] is the rigid pseudo-actor
};

}  // namespace vp
