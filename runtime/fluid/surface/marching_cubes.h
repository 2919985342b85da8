// The liquid surface (phi = 0) as an indexed triangle mesh by marching cubes over the cell
// centres of a level set (free_surface.h conventions).
//
// Mesh: one vertex per cube edge that the surface crosses (welded by edge id, so neighbouring
// cubes share it), placed by linear interpolation of phi; normals = grad phi (central
// differences at the nodes, interpolated like the position, normalized), pointing out of the
// liquid; triangles counter-clockwise seen from the air side (SurfaceMesh's "outside"). The
// node lattice is the cell centres plus one node on each domain side carrying the nearest
// cell's value, so the surface reaches the domain boundary and is cut there (open, not
// capped).
//
// Why written here rather than taken from a library: Debian (bookworm) has no libigl package,
// and OpenVDB's volumeToMesh or VTK's flying edges would bring large dependencies and a copy
// of the grid into their own structures every frame. The 256-case table is not pasted from
// anywhere: it is derived once at start-up from the cube faces. On each face the crossing
// edges are joined into segments around each run of liquid corners (on an ambiguous face,
// two diagonal liquid corners, each is cut off by its own segment); since that rule depends
// only on the face's four corners, two cubes sharing a face always make the same segments, so
// the surface is watertight with no ambiguity holes. Segments chain into loops (each crossing
// edge starts one segment and ends one), and each loop is fanned into triangles from an apex
// whose diagonals avoid the cube faces (a diagonal on a face would be shared with the
// neighbouring cube).
//
// Cost: two passes over the nodes and one over the cubes, parallel over z-slabs; output order
// is by slab, so the mesh is identical for any worker count.
#pragma once

#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/solids/face_fraction_field.h"
#include "geometry/surface_mesh.h"

namespace vp {

struct MarchingCubesWorkspace {
  Array<int32_t> firstVertex;  // per node: index of its first crossing edge's vertex
  Array<uint8_t> nodeBits;     // per node: bits 0-2 crossing edges along +x, +y, +z; bit 3 liquid
  Array<int64_t> slabCount;
};

// phi: cellCount values. normals gets one unit vector per mesh vertex.
Status extractLiquidSurface(TaskSystem& tasks, const MacGridSpec& grid, const double* phi, SurfaceMesh* mesh,
                            Array<Eigen::Vector3d>* normals, MarchingCubesWorkspace& workspace);

}  // namespace vp
