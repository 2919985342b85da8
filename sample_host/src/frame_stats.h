/* Per-frame samples for the sample host's summary (frame times, the deformables' residuals):
 * percentiles and the mean over the frames it ran. */
#ifndef VP_SAMPLE_FRAME_STATS_H
#define VP_SAMPLE_FRAME_STATS_H

typedef struct FrameTimes {
  double* ms;
  int count;
  int capacity;
} FrameTimes;

int frameTimesInit(FrameTimes* t, int capacity);
void frameTimesAdd(FrameTimes* t, double ms);
/* q in [0, 1]; nearest-rank percentile of the frames so far. */
double frameTimesPercentile(const FrameTimes* t, double q);
double frameTimesMean(const FrameTimes* t);
void frameTimesFree(FrameTimes* t);

#endif
