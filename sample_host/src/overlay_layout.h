/* The overlay text laid out for an image width: the glyph scale (larger where there is room) and
 * the lines wrapped at spaces so none runs past the right edge; a continuation is indented. */
#ifndef VP_SAMPLE_OVERLAY_LAYOUT_H
#define VP_SAMPLE_OVERLAY_LAYOUT_H

#define OVERLAY_MARGIN_PX 8.0f
#define OVERLAY_MAX_LINES 48
#define OVERLAY_LINE_CHARS 200

typedef struct OverlayLayout {
  float scale;     /* glyph scale over stb_easy_font's 6-pixel-wide characters */
  int lineCount;
  char lines[OVERLAY_MAX_LINES][OVERLAY_LINE_CHARS];
} OverlayLayout;

/* Lines past OVERLAY_MAX_LINES after wrapping are dropped. */
void overlayLayout(const char* const* lines, int lineCount, int widthPx, OverlayLayout* out);

/* The width in pixels of a laid-out line at the layout's scale. */
float overlayLineWidthPx(const OverlayLayout* layout, const char* line);

#endif
