"""Plain-Python views of vpStepStats / vpActorStats (copied out, so they outlive the step)."""
from dataclasses import dataclass, field
from typing import Dict

from ._types import PHASE_COUNT, ActorKind, Device, Phase


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
    fluid_interval: int  # the largest interval among the fluids (budget pacing)
    over_budget_ms: float    # how far total_ms went past budget_ms; 0 within it or unlimited
    budget_infeasible: bool  # the accuracy floors and minimum rates did not fit: some actor ran at its interval cap
    max_slice_ms: float      # the longest single slice of work in this step

    @classmethod
    def _from_c(cls, s):
        return cls(step_index=s.stepIndex, dt=s.dt, total_ms=s.totalMs, budget_ms=s.budgetMs,
                   budget_cut=bool(s.budgetCut), actor_count=s.actorCount, collider_count=s.colliderCount,
                   rigid_substeps=s.rigidSubsteps, fluid_interval=s.fluidInterval, over_budget_ms=s.overBudgetMs,
                   budget_infeasible=bool(s.budgetInfeasible), max_slice_ms=s.maxSliceMs)


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
    simulated_dt: float  # 0 unless a step completed in this frame
    interval: int         # frames per step (a fluid: frames its last completed step spanned)
    completed_step: bool  # a step of this actor completed in this frame
    progress: float       # fluid: fraction of its current step done, 1 when it completed
    slices: int           # slices of its work run in this frame
    residual: float       # final relative residual of its iterative solve in this frame
    priority: int         # the def's priority
    floor_missed: bool    # deformable: its solve ended the frame above its target_residual
    phases: Dict[Phase, PhaseStats] = field(default_factory=dict)
    failed_phases: tuple = ()  # phases that hit an error in this frame (World.step raised PhaseFailedError)
    device: Device = Device.Cpu  # where its solve ran in this frame

    @classmethod
    def _from_c(cls, s):
        # Only the phases this version knows; the C array has room for VP_MAX_PHASES.
        phases = {Phase(i): PhaseStats(p.ms, p.iterations, p.residual, bool(p.budgetCut))
                  for i, p in enumerate(s.phases[:PHASE_COUNT])}
        try:
            kind = ActorKind(s.kind)
        except ValueError:
            kind = s.kind
        return cls(kind=kind, index1=s.index1, total_ms=s.totalMs, diverged=bool(s.diverged),
                   simulated_dt=s.simulatedDt, interval=s.interval, completed_step=bool(s.completedStep),
                   progress=s.progress, slices=s.slices, residual=s.residual, priority=s.priority,
                   floor_missed=bool(s.floorMissed), phases=phases,
                   failed_phases=tuple(Phase(i) for i in range(PHASE_COUNT) if s.failedPhases & (1 << i)),
                   device=Device(s.device) if s.device in (1, 2) else s.device)
