#include "cli_values.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cliInt(const char* program, const char* flag, const char* text, int lo, int hi, int* out) {
  char* end;
  long v;
  errno = 0;
  v = strtol(text, &end, 10);
  if (errno || end == text || *end || v < lo || v > hi) {
    fprintf(stderr, "%s: %s = '%s': expected an integer in [%d, %d]\n", program, flag, text, lo, hi);
    return 0;
  }
  *out = (int)v;
  return 1;
}

int cliDouble(const char* program, const char* flag, const char* text, double lo, double hi, double* out) {
  char* end;
  double v;
  errno = 0;
  v = strtod(text, &end);
  if (errno || end == text || *end || !(v >= lo && v <= hi)) {
    fprintf(stderr, "%s: %s = '%s': expected a number in [%g, %g]\n", program, flag, text, lo, hi);
    return 0;
  }
  *out = v;
  return 1;
}

int cliSize(const char* program, const char* flag, const char* text, int lo, int hi, int* width, int* height) {
  int w, h;
  char tail;
  if (sscanf(text, "%dx%d%c", &w, &h, &tail) != 2 || w < lo || h < lo || w > hi || h > hi) {
    fprintf(stderr, "%s: %s = '%s': expected WIDTHxHEIGHT, each in [%d, %d]\n", program, flag, text, lo, hi);
    return 0;
  }
  *width = w;
  *height = h;
  return 1;
}

int cliChoice(const char* program, const char* flag, const char* text, const char* const* choices, int count, int* out) {
  int i;
  for (i = 0; i < count; ++i)
    if (strcmp(text, choices[i]) == 0) {
      *out = i;
      return 1;
    }
  fprintf(stderr, "%s: %s = '%s': expected one of", program, flag, text);
  for (i = 0; i < count; ++i) fprintf(stderr, "%s %s", i ? "," : "", choices[i]);
  fputc('\n', stderr);
  return 0;
}
