/* RGBA8 pixels to a PNG file (stb_image_write from Debian's libstb-dev). */
#ifndef VP_SAMPLE_PNG_WRITER_H
#define VP_SAMPLE_PNG_WRITER_H

/* `bottomUp`: the first row in memory is the bottom of the image, as OpenGL reads pixels.
 * Returns 1 on success; on failure prints why on stderr. */
int pngWriteRgba(const char* path, int width, int height, const unsigned char* pixels, int bottomUp);

#endif
