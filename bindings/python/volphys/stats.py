"""Plain-Python views of vpStepStats / vpActorStats (copied out, so they outlive the step)."""
from dataclasses import dataclass, field
from typing import Dict

from ._types import PHASE_COUNT, ActorKind, Phase


@dataclass(frozen=True)
class StepStats:
    step_index: int
    dt: float
    total_ms: float
    budget_ms: float     # 0 = unlimited
    budget_cut: bool
    actor_count: int
    collider_count: int
    rigid_substeps: int
    fluid_interval: int  # each fluid steps every fluid_interval steps (budget pacing)

    @classmethod
    def _from_c(cls, s):
        return cls(s.stepIndex, s.dt, s.totalMs, s.budgetMs, bool(s.budgetCut), s.actorCount,
                   s.colliderCount, s.rigidSubsteps, s.fluidInterval)


@dataclass(frozen=True)
class PhaseStats:
    ms: float
    iterations: int
    residual: float
    budget_cut: bool


@dataclass(frozen=True)
class ActorStats:
    kind: ActorKind
    index1: int
    total_ms: float
    diverged: bool
    simulated_dt: float  # 0 for a fluid the budget's pacing deferred
    phases: Dict[Phase, PhaseStats] = field(default_factory=dict)

    @classmethod
    def _from_c(cls, s):
        # Only the phases this version knows; the C array has room for VP_MAX_PHASES.
        phases = {Phase(i): PhaseStats(p.ms, p.iterations, p.residual, bool(p.budgetCut))
                  for i, p in enumerate(s.phases[:PHASE_COUNT])}
        try:
            kind = ActorKind(s.kind)
        except ValueError:
            kind = s.kind
        return cls(kind, s.index1, s.totalMs, bool(s.diverged), s.simulatedDt, phases)
