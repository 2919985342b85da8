/* Frame time against the budget as an SVG line chart, written directly (no plotting library
 * needed by the C host; the Python example shows the matplotlib version). */
#ifndef VP_SAMPLE_FRAME_PLOT_H
#define VP_SAMPLE_FRAME_PLOT_H

typedef struct FramePlot {
  float* stepMs;
  float* budgetMs;
  int* cut;
  int count, capacity;
} FramePlot;

int framePlotInit(FramePlot* p, int capacity);
void framePlotAdd(FramePlot* p, float stepMs, float budgetMs, int cut);
/* Step time per frame (cut frames marked), the budget as a dashed line. 1 on success. */
int framePlotWriteSvg(const FramePlot* p, const char* path);
void framePlotFree(FramePlot* p);

#endif
