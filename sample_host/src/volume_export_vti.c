#include "volume_export_vti.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

static const char* byteOrder(void) {
  const uint16_t one = 1;
  unsigned char first;
  memcpy(&first, &one, 1);
  return first ? "LittleEndian" : "BigEndian";
}

static int fail(const char* path, FILE* f) {
  fprintf(stderr, "volume export: cannot write '%s': %s\n", path, strerror(errno));
  if (f) fclose(f);
  return 0;
}

int volumeExportVti(const VolumeGrids* v, const char* path) {
  const uint64_t bytes = sizeof(float) * (uint64_t)v->nx * (uint64_t)v->ny * (uint64_t)v->nz;
  FILE* f = fopen(path, "wb");
  int g;
  if (!f) return fail(path, NULL);
  fprintf(f, "<?xml version=\"1.0\"?>\n");
  fprintf(f, "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"%s\" header_type=\"UInt64\">\n", byteOrder());
  fprintf(f, "  <ImageData WholeExtent=\"0 %d 0 %d 0 %d\" Origin=\"%.9g %.9g %.9g\" Spacing=\"%.9g %.9g %.9g\">\n",
          (int)v->nx, (int)v->ny, (int)v->nz, v->origin[0], v->origin[1], v->origin[2], v->cellSize, v->cellSize,
          v->cellSize);
  fprintf(f, "    <Piece Extent=\"0 %d 0 %d 0 %d\">\n", (int)v->nx, (int)v->ny, (int)v->nz);
  fprintf(f, "      <CellData Scalars=\"%s\">\n", v->gridCount > 0 ? v->grids[0].name : "");
  for (g = 0; g < v->gridCount; ++g)
    fprintf(f, "        <DataArray type=\"Float32\" Name=\"%s\" format=\"appended\" offset=\"%llu\"/>\n",
            v->grids[g].name, (unsigned long long)(g * (sizeof(uint64_t) + bytes)));
  fprintf(f, "      </CellData>\n    </Piece>\n  </ImageData>\n  <AppendedData encoding=\"raw\">\n   _");
  for (g = 0; g < v->gridCount; ++g)
    if (fwrite(&bytes, sizeof bytes, 1, f) != 1 || fwrite(v->grids[g].values, 1, (size_t)bytes, f) != bytes)
      return fail(path, f);
  fprintf(f, "\n  </AppendedData>\n</VTKFile>\n");
  if (ferror(f)) return fail(path, f);
  if (fclose(f) != 0) return fail(path, NULL);
  return 1;
}
