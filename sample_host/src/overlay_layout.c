#include "overlay_layout.h"

#include <string.h>

/* stb_easy_font is header-only with static functions: each file that measures includes it. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

static const char kIndent[] = "    ";

float overlayLineWidthPx(const OverlayLayout* layout, const char* line) {
  return layout->scale * (float)stb_easy_font_width((char*)line);
}

/* Appends `text` as lines no wider than maxPx, breaking at spaces (a single word wider than the
 * line stays whole). */
static void wrapLine(OverlayLayout* out, const char* text, float maxPx) {
  const char* rest = text;
  int first = 1;
  while (*rest && out->lineCount < OVERLAY_MAX_LINES) {
    char* line = out->lines[out->lineCount++];
    size_t used = 0, fit = 0;
    const char* p = rest;
    if (!first) {
      strcpy(line, kIndent);
      used = strlen(kIndent);
    }
    /* Take words while the line still fits. */
    while (*p) {
      const char* end = strchr(p, ' ');
      size_t len = end ? (size_t)(end - p) : strlen(p);
      size_t before = used;
      if (used + len + 1 >= OVERLAY_LINE_CHARS) break;
      memcpy(line + used, p, len);
      line[used + len] = '\0';
      if (fit > 0 && overlayLineWidthPx(out, line) > maxPx) {
        line[before] = '\0';
        used = before;
        break;
      }
      used += len;
      ++fit;
      p += len;
      if (*p == ' ') {
        line[used++] = ' ';
        line[used] = '\0';
        ++p;
      }
    }
    while (used > 0 && line[used - 1] == ' ') line[--used] = '\0';
    rest = p;
    first = 0;
  }
}

void overlayLayout(const char* const* lines, int lineCount, int widthPx, OverlayLayout* out) {
  const float maxPx = (float)widthPx - 2.0f * OVERLAY_MARGIN_PX;
  int i;
  memset(out, 0, sizeof *out);
  out->scale = widthPx >= 900 ? 1.5f : 1.15f;
  for (i = 0; i < lineCount; ++i) wrapLine(out, lines[i], maxPx);
}
