// The cantilever-beam tet mesh shared by the deformable-beam benchmarks (VolPhys' own solver
// and the Bullet comparison), so both solve exactly the same discrete problem.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/tet_mesh.h"

namespace vp::bench {

// A box [0, lengthX] x [0, sizeY] x [0, sizeZ] cut into cellsX * cellsY * cellsZ cubes (boxes),
// each split into 6 tets. Y is up (gravity is -Y in the benchmarks).
struct BeamMesh {
  std::vector<double> vertices;         // xyz per vertex, 3 doubles each
  std::vector<int32_t> tets;            // 4 vertex indices per tet, positively oriented:
                                        // (x1 - x0) . ((x2 - x0) x (x3 - x0)) > 0
  std::vector<int32_t> fixedVertices;   // every vertex with x == 0 (the clamped face)
  int32_t tipVertex = -1;               // centre of the free end face: x = L, y = sizeY / 2,
                                        // z = sizeZ / 2 (on the neutral axis). With an odd cell
                                        // count in Y or Z the grid line just below the centre.
  int32_t vertexCount() const { return static_cast<int32_t>(vertices.size() / 3); }
  int32_t tetCount() const { return static_cast<int32_t>(tets.size() / 4); }
};

// Cubes are split into 6 tets around the main diagonal (corner 000 to corner 111, Kuhn /
// Freudenthal split). Every cube uses the same diagonal, so the faces of neighbouring cubes are
// cut the same way and the mesh is conforming. tetCount = 6 * cellsX * cellsY * cellsZ.
BeamMesh makeBeamMesh(int cellsX, int cellsY, int cellsZ, double lengthX, double sizeY, double sizeZ);

// The beams have 4:1:1 cells (cellsX = 4n, cellsY = cellsZ = n), so a benchmark argument
// that is a tet count names a beam: 12288 -> 32x8x8, 98304 -> 64x16x16.
struct BeamCells {
  int x = 0, y = 0, z = 0;
};
// Returns false when tetCount is not 24 * n^3 for a whole n >= 1.
bool beamCellsForTetCount(int64_t tetCount, BeamCells* cells);
// For tet counts of no 4n x n x n beam (issue 6's "about 13K" quadratic tets): n x n cells
// across, n = round(cbrt(tetCount / 24)), and the cell count along x that brings 6 x n n
// nearest to tetCount (cells then are boxes, not cubes). Exact counts give the 4n x n x n
// beam. Returns false for tetCount < 24.
bool beamCellsNearTetCount(int64_t tetCount, BeamCells* cells);

// The beam as the runtime's tet mesh (same vertex and tet order).
TetMesh toTetMesh(const BeamMesh& mesh);

// Signed volume of tet (a, b, c, d): positive when positively oriented.
double signedTetVolume(const BeamMesh& mesh, int32_t tet);

// Checks what the benchmarks rely on: every tet has positive volume and the volumes sum to
// expectedVolume (relative tolerance 1e-9). Returns an empty string when the mesh is sound,
// otherwise a sentence saying what is wrong (for state.SkipWithError).
std::string findBeamMeshDefect(const BeamMesh& mesh, double expectedVolume);

}  // namespace vp::bench
