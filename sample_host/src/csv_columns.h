/* The fixed columns of the host's CSV files. Actor labels (actor_labels.h) are chosen so that
 * an actor's own columns (LABEL_ms, LABEL_px, ...) never repeat one of these. */
#ifndef VP_SAMPLE_CSV_COLUMNS_H
#define VP_SAMPLE_CSV_COLUMNS_H

/* stats.csv: the frame's totals, before the deformables' and fluids' own columns. */
#define STATS_CSV_TOTAL_COLUMNS                                                                              \
  "frame,step_ms,wall_ms,budget_ms,budget_cut,rigid_ms,rigid_substeps,colliders,actors,"                    \
  "deform_ms,deform_solve_ms,deform_iters,deform_max_residual,fluid_ms,fluid_advect_ms,fluid_forces_ms,"   \
  "fluid_fractions_ms,fluid_pressure_ms,fluid_pressure_iters,fluid_pressure_max_residual,fluid_surface_ms," \
  "fluid_interval,diverged"

/* poses.csv: the exported frame and its simulated time, before the colliders' columns. */
#define POSES_CSV_FIXED_COLUMNS "frame,time_s"

#endif
