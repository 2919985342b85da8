/* Writes a fluid's grids (volume_grids.h) as VTK XML image data (.vti) for ParaView. Written
 * here rather than through VTK: the format is a few lines of XML and the arrays' bytes, and
 * the host needs no VTK build for it. */
#ifndef VP_SAMPLE_VOLUME_EXPORT_VTI_H
#define VP_SAMPLE_VOLUME_EXPORT_VTI_H

#include "volume_grids.h"

/* One VTK cell per fluid cell: Origin is the domain's low corner, Spacing the cell size,
 * WholeExtent 0..nx, 0..ny, 0..nz in points, and each field a Float32 CellData array of every
 * cell (x fastest, as VTK orders cells) in raw appended binary (UInt64 byte counts, the
 * machine's byte order), as ParaView writes it. Returns 1 on success, else 0 with a message. */
int volumeExportVti(const VolumeGrids* volume, const char* path);

#endif
