#include "png_writer.h"

#include <stdio.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

int pngWriteRgba(const char* path, int width, int height, const unsigned char* pixels, int bottomUp) {
  int ok;
  stbi_flip_vertically_on_write(bottomUp);
  ok = stbi_write_png(path, width, height, 4, pixels, 4 * width);
  if (!ok) fprintf(stderr, "cannot write PNG '%s'\n", path);
  return ok;
}
