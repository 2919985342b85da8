#include "frame_stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int frameTimesInit(FrameTimes* t, int capacity) {
  t->ms = (double*)malloc(sizeof(double) * (size_t)(capacity > 0 ? capacity : 1));
  t->count = 0;
  t->capacity = capacity;
  return t->ms != NULL;
}

void frameTimesAdd(FrameTimes* t, double ms) {
  if (t->count < t->capacity) t->ms[t->count++] = ms;
}

static int compareDoubles(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

double frameTimesPercentile(const FrameTimes* t, double q) {
  double* sorted;
  double result;
  int rank;
  if (t->count == 0) return 0.0;
  sorted = (double*)malloc(sizeof(double) * (size_t)t->count);
  if (!sorted) return 0.0;
  memcpy(sorted, t->ms, sizeof(double) * (size_t)t->count);
  qsort(sorted, (size_t)t->count, sizeof(double), compareDoubles);
  rank = (int)ceil(q * t->count) - 1;
  if (rank < 0) rank = 0;
  if (rank >= t->count) rank = t->count - 1;
  result = sorted[rank];
  free(sorted);
  return result;
}

double frameTimesMean(const FrameTimes* t) {
  double sum = 0.0;
  int i;
  for (i = 0; i < t->count; ++i) sum += t->ms[i];
  return t->count ? sum / t->count : 0.0;
}

void frameTimesFree(FrameTimes* t) {
  free(t->ms);
  t->ms = NULL;
  t->count = t->capacity = 0;
}
