/* Writes one ViewMesh (in world space: its pose applied) to a file with assimp's exporter.
 * C++ inside, C outside, so the host stays a C program. */
#ifndef VP_SAMPLE_MESH_EXPORT_H
#define VP_SAMPLE_MESH_EXPORT_H

#include "scene_view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* `format` is an assimp export format id: "ply" (ASCII PLY), "plyb", "obj", "stl", ...
 * Returns 1 on success; on failure prints assimp's reason on stderr. */
int meshExportWrite(const ViewMesh* mesh, const char* format, const char* path);
/* 1 if assimp knows the format id. */
int meshExportFormatKnown(const char* format);

#ifdef __cplusplus
}
#endif

#endif
