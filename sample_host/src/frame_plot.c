#include "frame_plot.h"

#include "run_summary.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int framePlotInit(FramePlot* p, int capacity) {
  memset(p, 0, sizeof *p);
  if (capacity < 1) capacity = 1;
  p->stepMs = (float*)malloc(sizeof(float) * (size_t)capacity);
  p->budgetMs = (float*)malloc(sizeof(float) * (size_t)capacity);
  p->cut = (int*)malloc(sizeof(int) * (size_t)capacity);
  p->capacity = capacity;
  return p->stepMs && p->budgetMs && p->cut;
}

void framePlotAdd(FramePlot* p, float stepMs, float budgetMs, int cut) {
  if (p->count >= p->capacity) return;
  p->stepMs[p->count] = stepMs;
  p->budgetMs[p->count] = budgetMs;
  p->cut[p->count] = cut;
  ++p->count;
}

/* A "nice" tick step (1, 2 or 5 times a power of ten) giving about `target` ticks. */
static double tickStep(double range, int target) {
  double raw = range / target, mag = pow(10.0, floor(log10(raw))), r = raw / mag;
  return (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * mag;
}

int framePlotWriteSvg(const FramePlot* p, const char* path) {
  const double W = 800, H = 430, left = 60, right = 20, top = 62, bottom = 50;
  const double pw = W - left - right, ph = H - top - bottom;
  double ymax = 1.0, ystep, v;
  int i, xmax = p->count > 1 ? p->count - 1 : 1;
  FILE* f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "cannot write '%s'\n", path);
    return 0;
  }
  for (i = 0; i < p->count; ++i) {
    if (p->stepMs[i] > ymax) ymax = p->stepMs[i];
    if (p->budgetMs[i] > ymax) ymax = p->budgetMs[i];
  }
  ymax *= 1.1;
#define X(i) (left + pw * (double)(i) / xmax)
#define Y(ms) (top + ph * (1.0 - (ms) / ymax))
  fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" font-family=\"sans-serif\" "
             "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n", W, H);
  fprintf(f, "<text x=\"%g\" y=\"18\" font-size=\"14\">VolPhys step time per frame against the budget</text>\n", left);
  ystep = tickStep(ymax, 6);
  for (v = 0; v <= ymax; v += ystep)
    fprintf(f, "<line x1=\"%g\" y1=\"%.1f\" x2=\"%g\" y2=\"%.1f\" stroke=\"#ddd\"/><text x=\"%g\" y=\"%.1f\" "
               "text-anchor=\"end\">%g</text>\n", left, Y(v), left + pw, Y(v), left - 6, Y(v) + 4, v);
  for (v = 0; v <= xmax; v += tickStep(xmax, 8))
    fprintf(f, "<text x=\"%.1f\" y=\"%g\" text-anchor=\"middle\">%g</text>\n", X(v), top + ph + 18, v);
  fprintf(f, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">frame</text>\n", left + pw / 2, H - 8);
  fprintf(f, "<text transform=\"translate(16,%g) rotate(-90)\" text-anchor=\"middle\">ms</text>\n", top + ph / 2);
  fprintf(f, "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" stroke=\"black\"/>\n", left, top, pw, ph);
  if (p->count > 0) {
    /* Step time under the budget, so the budget line stays on top; budget-cut frames are ticks
     * along the bottom edge, frames over RUN_SUMMARY_OVER_BUDGET_FACTOR x budget red dots on the step line. */
    fprintf(f, "<polyline id=\"step_time\" fill=\"none\" stroke=\"#25a\" points=\"");
    for (i = 0; i < p->count; ++i) fprintf(f, "%.1f,%.1f ", X(i), Y(p->stepMs[i]));
    fprintf(f, "\"/>\n<polyline id=\"over_budget\" fill=\"none\" stroke=\"#e80\" stroke-dasharray=\"2,3\" points=\"");
    for (i = 0; i < p->count; ++i) fprintf(f, "%.1f,%.1f ", X(i), Y(RUN_SUMMARY_OVER_BUDGET_FACTOR * p->budgetMs[i]));
    fprintf(f, "\"/>\n<polyline id=\"budget\" fill=\"none\" stroke=\"#e80\" stroke-width=\"2.5\" points=\"");
    for (i = 0; i < p->count; ++i) fprintf(f, "%.1f,%.1f ", X(i), Y(p->budgetMs[i]));
    fprintf(f, "\"/>\n");
    for (i = 0; i < p->count; ++i) {
      if (p->cut[i])
        fprintf(f, "<line x1=\"%.1f\" y1=\"%g\" x2=\"%.1f\" y2=\"%g\" stroke=\"#999\"/>\n", X(i), top + ph,
                X(i), top + ph - 6);
      if (p->budgetMs[i] > 0 && p->stepMs[i] > RUN_SUMMARY_OVER_BUDGET_FACTOR * p->budgetMs[i])
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"#c00\"/>\n", X(i), Y(p->stepMs[i]));
    }
  }
  fprintf(f, "<text x=\"%g\" y=\"%g\" fill=\"#25a\">step time</text><text x=\"%g\" y=\"%g\" fill=\"#e80\">"
             "budget (0 = unlimited), dashed: %gx budget</text><text x=\"%g\" y=\"%g\" fill=\"#c00\">"
             "dots: frames over %gx budget</text><text x=\"%g\" y=\"%g\" fill=\"#777\">ticks: budget-cut frames"
             "</text>\n</svg>\n",
          left, top - 26, left + 80, top - 26, RUN_SUMMARY_OVER_BUDGET_FACTOR, left, top - 10, RUN_SUMMARY_OVER_BUDGET_FACTOR,
          left + 190, top - 10);
#undef X
#undef Y
  return fclose(f) == 0;
}

void framePlotFree(FramePlot* p) {
  free(p->stepMs);
  free(p->budgetMs);
  free(p->cut);
  memset(p, 0, sizeof *p);
}
