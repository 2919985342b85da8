/* VolPhys sample host: loads a scene through the C ABI, steps it headless, prints one line of
 * stats per frame and a summary, and writes its outputs to an output folder: per-frame stats
 * CSV, a frame-time plot (SVG), and every few frames the collider poses (CSV), meshes of the
 * deformables and liquid surfaces (assimp), the fluids' volumes (OpenVDB or VTK image data)
 * and PNG snapshots (offscreen OSMesa). Talks to VolPhys through nothing but volphys.h; the
 * exporters are C++ files only because assimp's and OpenVDB's interfaces are C++. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "actor_labels.h"
#include "cli_values.h"
#include "csv_columns.h"
#include "default_scene.h"
#include "frame_plot.h"
#include "frame_stats.h"
#include "mesh_quality_report.h"
#include "host_outputs.h"
#include "phase_names.h"
#include "run_summary.h"
#include "step_summary.h"
#include "volphys/volphys.h"

typedef struct Options {
  const char* scene;
  const char* outDir;
  int frames;
  double dt;
  int workers;
  int device; /* a vpDevice */
  double budgetMs; /* < 0: keep the scene's */
  int quiet;
  HostOutputsConfig outputs;
} Options;

static void usage(FILE* f) {
  fprintf(f,
          "usage: volphys_host [--scene FILE] [--frames N] [--dt SECONDS] [--workers N]\n"
          "                    [--budget MS] [--device cpu|auto|cuda] [--out DIR] [--quiet]\n"
          "                    [--export-every N] [--export-format ID] [--export-volumes vdb|vti|none]\n"
          "                    [--snapshot-every N] [--image-size WxH]\n"
          "Steps the scene headless, prints per-frame stats, writes DIR/stats.csv, DIR/frame_times.svg;\n"
          "every --export-every frames DIR/poses.csv rows (collider poses by name), DIR/meshes/NAME_fNNNNN.EXT\n"
          "(deformables, liquid surfaces; assimp format id: ply, plyb, obj, stl, ...) and with\n"
          "--export-volumes DIR/volumes/NAME_fNNNNN.vdb or .vti (smoke density and temperature, liquid\n"
          "level set); DIR/meshes/NAME.EXT once per collider (its local frame); and\n"
          "DIR/snapshots/frame_NNNNN.png every --snapshot-every frames (all also on the last frame;\n"
          "0 = off). NAME: the scene's name of the actor, or colliderK, deformableK, fluidK.\n"
          "--device: where the deformables' implicit solves run (vpWorldDef.device; cuda needs a GPU).\n"
          "Defaults: the bundled default scene, 300 frames, dt 1/60, 2 workers, cpu, out/sample,\n"
          "export every 30 frames as ply, no volumes, snapshot every 60 frames at 640x480.\n");
}

static int parseOptions(int argc, char** argv, Options* o) {
  static const char* const kVolumeFormats[3] = {"none", "vdb", "vti"}; /* indexed by VolumeFormat */
  static const char* const kDevices[3] = {"auto", "cpu", "cuda"};      /* indexed by vpDevice */
  int i, volumeFormat = VolumeFormat_None;
  o->scene = defaultScenePath();
  o->outDir = "out/sample";
  o->frames = 300;
  o->dt = 1.0 / 60.0;
  o->workers = 2;
  o->device = vpDevice_Cpu;
  o->budgetMs = -1.0;
  o->quiet = 0;
  o->outputs.exportEvery = 30;
  o->outputs.exportFormat = "ply";
  o->outputs.snapshotEvery = 60;
  o->outputs.imageWidth = 640;
  o->outputs.imageHeight = 480;
  for (i = 1; i < argc; ++i) {
    const char* a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      usage(stdout);
      exit(0);
    } else if (!strcmp(a, "--quiet")) {
      o->quiet = 1;
      continue;
    }
    if (!v) {
      fprintf(stderr, "volphys_host: %s needs a value\n", a);
      return 0;
    }
    ++i;
    if (!strcmp(a, "--scene")) o->scene = v;
    else if (!strcmp(a, "--out")) o->outDir = v;
    else if (!strcmp(a, "--frames")) { if (!cliInt("volphys_host", a, v, 1, 10000000, &o->frames)) return 0; }
    else if (!strcmp(a, "--dt")) { if (!cliDouble("volphys_host", a, v, 1e-5, 1.0, &o->dt)) return 0; }
    else if (!strcmp(a, "--workers")) { if (!cliInt("volphys_host", a, v, 1, 64, &o->workers)) return 0; }
    else if (!strcmp(a, "--device")) { if (!cliChoice("volphys_host", a, v, kDevices, 3, &o->device)) return 0; }
    else if (!strcmp(a, "--budget")) { if (!cliDouble("volphys_host", a, v, 0.0, 1e4, &o->budgetMs)) return 0; }
    else if (!strcmp(a, "--export-every")) { if (!cliInt("volphys_host", a, v, 0, 10000000, &o->outputs.exportEvery)) return 0; }
    else if (!strcmp(a, "--export-format")) o->outputs.exportFormat = v;
    else if (!strcmp(a, "--export-volumes")) { if (!cliChoice("volphys_host", a, v, kVolumeFormats, 3, &volumeFormat)) return 0; }
    else if (!strcmp(a, "--snapshot-every")) { if (!cliInt("volphys_host", a, v, 0, 10000000, &o->outputs.snapshotEvery)) return 0; }
    else if (!strcmp(a, "--image-size")) {
      if (!cliSize("volphys_host", a, v, 16, 8192, &o->outputs.imageWidth, &o->outputs.imageHeight)) return 0;
    }
    else {
      fprintf(stderr, "volphys_host: unknown option '%s'\n", a);
      usage(stderr);
      return 0;
    }
  }
  o->outputs.volumeFormat = (VolumeFormat)volumeFormat;
  o->outputs.dt = o->dt;
  if (o->outputs.volumeFormat != VolumeFormat_None && o->outputs.exportEvery == 0) {
    fprintf(stderr, "volphys_host: --export-volumes = '%s' with --export-every = 0: volumes are written on the "
                    "export frames; give --export-every N > 0 or --export-volumes none\n", kVolumeFormats[volumeFormat]);
    return 0;
  }
  return 1;
}

static double wallMs(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static FILE* openOutput(const char* dir, const char* name) {
  char path[4096];
  FILE* f;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  f = fopen(path, "w");
  if (!f) fprintf(stderr, "volphys_host: cannot write '%s': %s\n", path, strerror(errno));
  return f;
}

static int fail(const char* what, vpStatus status) {
  fprintf(stderr, "volphys_host: %s failed (%s): %s\n", what, vpStatusName(status), vpGetLastError());
  return 1;
}

/* stats.csv: totals by kind, then each actor's own columns, named by its label like its files
 * (actor_labels.h): its ms, each of its kind's phases in ms, and its iterative phase's
 * iterations and residual; a fluid also its simulated time (0 unless a step of it completed
 * in that frame); then the frame plan's view of it: its interval, progress, slices and final
 * residual. */
typedef struct ActorColumns {
  vpActorKind kind;
  int iterative; /* the phase whose iterations and residual are reported */
  int phases[8];
  int phaseCount;
} ActorColumns;

static const ActorColumns kActorColumns[] = {
    {vpActorKind_Deformable, vpPhase_Solve,
     {vpPhase_Corotate, vpPhase_Assemble, vpPhase_Contacts, vpPhase_Solve, vpPhase_Embed, vpPhase_Coupling}, 6},
    {vpActorKind_Fluid, vpPhase_Pressure,
     {vpPhase_Advect, vpPhase_Forces, vpPhase_Viscosity, vpPhase_Fractions, vpPhase_Pressure, vpPhase_Surface,
      vpPhase_Coupling},
     7},
};

static const ActorColumns* actorColumns(vpActorKind kind) {
  size_t i;
  for (i = 0; i < sizeof kActorColumns / sizeof kActorColumns[0]; ++i)
    if (kActorColumns[i].kind == kind) return &kActorColumns[i];
  return NULL;
}

static void writeStatsHeader(FILE* csv, vpWorldId world, const ActorLabels* labels, int actorCount) {
  int a, p;
  fprintf(csv, "%s", STATS_CSV_TOTAL_COLUMNS);
  for (a = 1; a < actorCount; ++a) {
    vpActorStats s = vpDefaultActorStats();
    const ActorColumns* c;
    const char* l;
    if (vpWorldGetActorStats(world, a, &s) != vpStatus_Ok || !(c = actorColumns(s.kind))) continue;
    if (!(l = actorLabelOfStats(labels, &s))) continue;
    fprintf(csv, ",%s_ms", l);
    if (s.kind == vpActorKind_Fluid) fprintf(csv, ",%s_sim_dt", l);
    for (p = 0; p < c->phaseCount; ++p) fprintf(csv, ",%s_%s_ms", l, phaseName(c->phases[p]));
    fprintf(csv, ",%s_%s_iters,%s_%s_residual", l, phaseName(c->iterative), l, phaseName(c->iterative));
    fprintf(csv, ",%s_interval,%s_progress,%s_slices,%s_residual", l, l, l, l);
  }
  fputc('\n', csv);
}

static void writeActorColumns(FILE* csv, vpWorldId world, const ActorLabels* labels, int actorCount) {
  int a, p;
  for (a = 1; a < actorCount; ++a) {
    vpActorStats s = vpDefaultActorStats();
    const ActorColumns* c;
    if (vpWorldGetActorStats(world, a, &s) != vpStatus_Ok || !(c = actorColumns(s.kind))) continue;
    if (!actorLabelOfStats(labels, &s)) continue;
    fprintf(csv, ",%.4f", s.totalMs);
    if (s.kind == vpActorKind_Fluid) fprintf(csv, ",%.5f", s.simulatedDt);
    for (p = 0; p < c->phaseCount; ++p) fprintf(csv, ",%.4f", s.phases[c->phases[p]].ms);
    fprintf(csv, ",%d,%.3e", s.phases[c->iterative].iterations, s.phases[c->iterative].residual);
    fprintf(csv, ",%d,%.4f,%d,%.3e", s.interval, s.progress, s.slices, s.residual);
  }
  fputc('\n', csv);
}

/* Steps the loaded world and writes every output; returns the exit code. */
static int run(vpWorldId world, const ActorLabels* labels, const Options* o) {
  vpStatus s;
  FrameTimes times;
  FramePlot plot;
  HostOutputs outputs;
  RunSummary summary;
  char plotPath[4096];
  FILE* csv = NULL;
  int frame, cutFrames = 0, rc = 1;
  vpStepStats stats = vpDefaultStepStats();

  memset(&times, 0, sizeof times);
  memset(&plot, 0, sizeof plot);
  memset(&outputs, 0, sizeof outputs);
  runSummaryInit(&summary, o->frames);
  if (!makeDirectories(o->outDir)) {
    fprintf(stderr, "volphys_host: cannot create output folder '%s': %s\n", o->outDir, strerror(errno));
    return 1;
  }
  if (!hostOutputsInit(&outputs, world, labels, &o->outputs)) goto done;
  csv = openOutput(o->outDir, "stats.csv");
  if (!csv || !frameTimesInit(&times, o->frames) || !framePlotInit(&plot, o->frames)) goto done;

  printf("volphys_host: scene %s, %d frames, dt %.5f s, %d workers, deformables' solves on %s\n", o->scene, o->frames,
         o->dt, o->workers, o->device == vpDevice_Cuda ? "cuda" : o->device == vpDevice_Auto ? "auto's choice" : "cpu");
  if (!printMeshQuality(stdout, labels)) goto done;
  for (frame = 0; frame < o->frames; ++frame) {
    vpActorStats rigid = vpDefaultActorStats();
    DeformSummary deform;
    FluidSummary fluid;
    double t0 = wallMs(), wall;
    s = vpWorldStep(world, (float)o->dt);
    if (s == vpStatus_PhaseFailed || s == vpStatus_OutOfMemory) {
      /* The step completed what it could and the world stays steppable: report and go on. */
      fprintf(stderr, "volphys_host: frame %d: %s: %s\n", frame, vpStatusName(s), vpGetLastError());
    } else if (s != vpStatus_Ok) {
      fail("vpWorldStep", s);
      goto done;
    }
    wall = wallMs() - t0;
    vpWorldGetStepStats(world, &stats);
    vpWorldGetActorStats(world, 0, &rigid);
    summarizeDeformables(world, stats.actorCount, &deform);
    summarizeFluids(world, stats.actorCount, &fluid);
    frameTimesAdd(&times, wall);
    framePlotAdd(&plot, stats.totalMs, stats.budgetMs, stats.budgetCut);
    cutFrames += stats.budgetCut;
    if (!runSummaryAdd(&summary, world, &stats)) {
      fprintf(stderr, "volphys_host: out of memory for the run summary\n");
      goto done;
    }
    /* The per-actor columns need the actors, which the first step lists. */
    if (frame == 0) writeStatsHeader(csv, world, labels, stats.actorCount);
    fprintf(csv, "%d,%.4f,%.4f,%.2f,%d,%.4f,%d,%d,%d,%.4f,%.4f,%d,%.3e,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%.3e,%.4f,%d,%d",
            frame, stats.totalMs, wall, stats.budgetMs, stats.budgetCut, rigid.phases[vpPhase_Rigid].ms,
            stats.rigidSubsteps, stats.colliderCount, stats.actorCount, deform.ms, deform.solveMs, deform.iterations,
            deform.maxResidual, fluid.ms, fluid.advectMs, fluid.forcesMs, fluid.fractionsMs, fluid.pressureMs,
            fluid.pressureIterations, fluid.maxResidual, fluid.surfaceMs, stats.fluidInterval,
            deform.diverged + fluid.diverged);
    writeActorColumns(csv, world, labels, stats.actorCount);
    if (!o->quiet)
      printf("frame %4d  step %7.3f ms  (budget %5.1f ms%s)  rigid %6.3f ms x%d  deform %7.3f ms, %3d CG its, "
             "res %.1e  fluid %7.3f ms, %3d p its, res %.1e%s\n",
             frame, stats.totalMs, stats.budgetMs, stats.budgetCut ? ", CUT" : "", rigid.phases[vpPhase_Rigid].ms,
             stats.rigidSubsteps, deform.ms, deform.iterations, deform.maxResidual, fluid.ms,
             fluid.pressureIterations, fluid.maxResidual, deform.diverged + fluid.diverged ? "  DIVERGED" : "");
    /* Outside the timed step: writing files is the host's cost, not the simulation's. */
    if (!hostOutputsFrame(&outputs, frame, o->frames)) goto done;
  }
  snprintf(plotPath, sizeof plotPath, "%s/frame_times.svg", o->outDir);
  if (!framePlotWriteSvg(&plot, plotPath)) goto done;
  printf("summary: %d frames, mean %.3f ms, p50 %.3f ms, p95 %.3f ms, max %.3f ms, budget-cut frames %d",
         times.count, frameTimesMean(&times), frameTimesPercentile(&times, 0.5), frameTimesPercentile(&times, 0.95),
         frameTimesPercentile(&times, 1.0), cutFrames);
  runSummaryPrint(&summary, labels, stdout);
  putchar('\n');
  printf("wrote %s/stats.csv, %s/poses.csv, %s, %d mesh files in %s/meshes, %d volume files in %s/volumes, "
         "%d snapshots in %s/snapshots\n",
         o->outDir, o->outDir, plotPath, outputs.meshFiles, o->outDir, outputs.volumeFiles, o->outDir,
         outputs.snapshotFiles, o->outDir);
  rc = 0;
done:
  if (csv) fclose(csv);
  hostOutputsFree(&outputs);
  runSummaryFree(&summary);
  framePlotFree(&plot);
  frameTimesFree(&times);
  return rc;
}

int main(int argc, char** argv) {
  Options o;
  ActorLabels labels;
  vpWorldDef def;
  vpWorldId world;
  vpStatus s;
  int rc;

  if (!parseOptions(argc, argv, &o)) return 2;
  if ((s = vpCheckVersion()) != vpStatus_Ok) return fail("version check", s);
  o.outputs.outDir = o.outDir;

  def = vpDefaultWorldDef();
  def.workerCount = o.workers;
  def.device = o.device;
  if ((s = vpWorldCreate(&def, &world)) != vpStatus_Ok) return fail("vpWorldCreate", s);
  if ((s = vpWorldLoadScene(world, o.scene)) != vpStatus_Ok)
    rc = fail("vpWorldLoadScene", s);
  else if (o.budgetMs >= 0.0 && (s = vpWorldSetFrameBudget(world, (float)o.budgetMs)) != vpStatus_Ok)
    rc = fail("vpWorldSetFrameBudget", s);
  else if (!actorLabelsInit(&labels, world))
    rc = 1;
  else {
    rc = run(world, &labels, &o);
    actorLabelsFree(&labels);
  }
  vpWorldDestroy(world);
  return rc;
}
