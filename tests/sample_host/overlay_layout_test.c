/* The HUD's lines wrapped to the image: at 640 px every line fits inside the margins and no
 * word is lost or split; at 1280 px the same lines need no wrapping. */
#include <stdio.h>
#include <string.h>

#include "overlay_layout.h"

static const char* const kLines[] = {
    "frame 240  step 16.32 ms / budget 16.0 ms  CUT  INFEASIBLE",
    "deformable jelly 2.38 ms: corotate 1.86 assemble 0.02 contacts 0.08 solve 0.33 (14 its, res 8e-03, cut) embed 0.09",
    "fluid tank 6.28 ms: advect 1.66 forces 0.00 fractions 3.45 surface 1.16 step 82% every 3 frames",
    "bullet 0.11 ms: rigid 0.11",
};
enum { kLineCount = sizeof kLines / sizeof kLines[0] };

/* The words of all lines, space-separated, in order. */
static void words(const char* const* lines, int count, char* out, size_t size) {
  int i;
  out[0] = '\0';
  for (i = 0; i < count; ++i) {
    const char* p = lines[i];
    while (*p) {
      while (*p == ' ') ++p;
      if (!*p) break;
      if (out[0]) strncat(out, " ", size - strlen(out) - 1);
      while (*p && *p != ' ') {
        const size_t n = strlen(out);
        if (n + 1 < size) out[n] = *p, out[n + 1] = '\0';
        ++p;
      }
    }
  }
}

static int check(int width, int expectWrapped) {
  static OverlayLayout layout;
  static char before[2048], after[2048];
  const char* laid[OVERLAY_MAX_LINES];
  int i;
  overlayLayout(kLines, kLineCount, width, &layout);
  for (i = 0; i < layout.lineCount; ++i) {
    const float w = overlayLineWidthPx(&layout, layout.lines[i]);
    laid[i] = layout.lines[i];
    if (w > (float)width - 2.0f * OVERLAY_MARGIN_PX) {
      printf("width %d: line %d is %.0f px: '%s'\n", width, i, w, layout.lines[i]);
      return 0;
    }
  }
  if ((layout.lineCount > kLineCount) != expectWrapped) {
    printf("width %d: %d lines from %d\n", width, layout.lineCount, kLineCount);
    return 0;
  }
  words(kLines, kLineCount, before, sizeof before);
  words(laid, layout.lineCount, after, sizeof after);
  if (strcmp(before, after) != 0) {
    printf("width %d: words changed:\n%s\n%s\n", width, before, after);
    return 0;
  }
  return 1;
}

int main(void) {
  if (!check(640, 1) || !check(1280, 0)) return 1;
  printf("overlay layout OK\n");
  return 0;
}
