// Marching cubes with a table derived from the cube faces (see marching_cubes.h).
#include "fluid/surface/marching_cubes.h"

#include <array>

#include "core/parallel_for.h"
#include "fluid/surface/free_surface.h"

namespace vp {
namespace {

// Cube corners: c = x + 2 y + 4 z (bits). Edges: e = 4 a + (u + 2 v) along axis a, with u, v
// the bits of the other two axes in increasing axis order.
int edgeBetween(int p, int q) {
  const int a = (p ^ q) == 1 ? 0 : (p ^ q) == 2 ? 1 : 2;
  int bits[3] = {p & 1, (p >> 1) & 1, (p >> 2) & 1};
  const int o1 = a == 0 ? 1 : 0, o2 = a == 2 ? 1 : 2;
  return 4 * a + bits[o1] + 2 * bits[o2];
}

// The two corners of an edge.
void edgeCorners(int e, int* p, int* q) {
  const int a = e / 4, u = e & 1, v = (e >> 1) & 1;
  const int o1 = a == 0 ? 1 : 0, o2 = a == 2 ? 1 : 2;
  *p = (u << o1) | (v << o2);
  *q = *p | (1 << a);
}

// True when both edges lie on one face of the cube (all their corners agree on some axis bit).
bool onCommonFace(int e1, int e2) {
  int c[4];
  edgeCorners(e1, &c[0], &c[1]);
  edgeCorners(e2, &c[2], &c[3]);
  for (int axis = 0; axis < 3; ++axis) {
    const int bit = (c[0] >> axis) & 1;
    if (((c[1] >> axis) & 1) == bit && ((c[2] >> axis) & 1) == bit && ((c[3] >> axis) & 1) == bit) return true;
  }
  return false;
}

struct CaseTriangles {
  int count = 0;
  std::array<std::array<int8_t, 3>, 12> edges{};
};

std::array<CaseTriangles, 256> buildTable() {
  std::array<CaseTriangles, 256> table;
  for (int mask = 0; mask < 256; ++mask) {
    auto inside = [&](int corner) { return (mask >> corner) & 1; };
    int next[12];
    for (int& n : next) n = -1;
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      for (int side = 0; side < 2; ++side) {
        // The face's corners counter-clockwise seen from outside the cube: (b, c) = (0,0),
        // (1,0), (1,1), (0,1) around +e_a (e_b x e_c = e_a), reversed around -e_a.
        static const int ccw[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        int q[4];
        for (int n = 0; n < 4; ++n) {
          const int* bc = ccw[side == 1 ? n : (4 - n) % 4];
          q[n] = (side << a) | (bc[0] << b) | (bc[1] << c);
        }
        // One segment per run of liquid corners, from the edge where the walk enters the run
        // to the edge where it leaves it: the surface's loop then runs counter-clockwise seen
        // from the air.
        for (int n = 0; n < 4; ++n) {
          if (!inside(q[n]) || inside(q[(n + 3) % 4])) continue;
          int last = n;
          while (inside(q[(last + 1) % 4])) last = (last + 1) % 4;
          next[edgeBetween(q[(n + 3) % 4], q[n])] = edgeBetween(q[last], q[(last + 1) % 4]);
        }
      }
    }
    bool used[12] = {};
    CaseTriangles& out = table[mask];
    for (int start = 0; start < 12; ++start) {
      if (next[start] < 0 || used[start]) continue;
      int loop[12], length = 0;
      for (int e = start; !used[e]; e = next[e]) {
        used[e] = true;
        loop[length++] = e;
      }
      // Fan from an apex whose diagonals stay off the cube's faces: a diagonal along a face
      // would also be an edge of the neighbouring cube's triangles there (it shares both
      // vertices), making that edge non-manifold.
      int apex = -1;
      for (int s = 0; s < length && apex < 0; ++s) {
        bool clean = true;
        for (int t = 2; t + 1 < length && clean; ++t) clean = !onCommonFace(loop[s], loop[(s + t) % length]);
        if (clean) apex = s;
      }
      // Every loop of the 256 cases has such an apex (the random-field test meets them all and
      // checks the surface is closed); 0 is only a fallback that keeps the table complete.
      if (apex < 0) apex = 0;
      for (int t = 1; t + 1 < length; ++t)
        out.edges[out.count++] = {static_cast<int8_t>(loop[apex]), static_cast<int8_t>(loop[(apex + t) % length]),
                                  static_cast<int8_t>(loop[(apex + t + 1) % length])};
    }
  }
  return table;
}

const std::array<CaseTriangles, 256>& caseTable() {
  static const std::array<CaseTriangles, 256> table = buildTable();
  return table;
}

// The node lattice: cell centres plus a node on each domain side (node index I = cell i + 1).
struct Lattice {
  const MacGridSpec& g;
  const double* phi;
  int n[3];
  explicit Lattice(const MacGridSpec& spec, const double* values) : g(spec), phi(values) {
    n[0] = g.nx + 2;
    n[1] = g.ny + 2;
    n[2] = g.nz + 2;
  }
  int cells(int a) const { return a == 0 ? g.nx : a == 1 ? g.ny : g.nz; }
  int cellOf(int a, int node) const {
    const int c = node - 1;
    return c < 0 ? 0 : c >= cells(a) ? cells(a) - 1 : c;
  }
  size_t cellIndex(int i, int j, int k) const {
    return static_cast<size_t>(i) + static_cast<size_t>(g.nx) * (j + static_cast<size_t>(g.ny) * k);
  }
  double value(int I, int J, int K) const { return phi[cellIndex(cellOf(0, I), cellOf(1, J), cellOf(2, K))]; }
  double coordinate(int a, int node) const {
    const double o = g.origin[a];
    if (node == 0) return o;
    if (node == n[a] - 1) return o + cells(a) * g.h;
    return o + (node - 0.5) * g.h;
  }
  size_t node(int I, int J, int K) const {
    return static_cast<size_t>(I) + static_cast<size_t>(n[0]) * (J + static_cast<size_t>(n[1]) * K);
  }
  // Bit a set when the edge from (I, J, K) along +a crosses the surface.
  int crossings(int I, int J, int K) const {
    const bool in = isLiquid(value(I, J, K));
    int mask = 0;
    if (I + 1 < n[0] && isLiquid(value(I + 1, J, K)) != in) mask |= 1;
    if (J + 1 < n[1] && isLiquid(value(I, J + 1, K)) != in) mask |= 2;
    if (K + 1 < n[2] && isLiquid(value(I, J, K + 1)) != in) mask |= 4;
    return mask;
  }
  // Central differences over cells (one-sided at the grid's ends), per metre.
  Eigen::Vector3d gradient(int I, int J, int K) const {
    const int c[3] = {cellOf(0, I), cellOf(1, J), cellOf(2, K)};
    Eigen::Vector3d grad;
    for (int a = 0; a < 3; ++a) {
      int lo[3] = {c[0], c[1], c[2]}, hi[3] = {c[0], c[1], c[2]};
      lo[a] = c[a] > 0 ? c[a] - 1 : c[a];
      hi[a] = c[a] + 1 < cells(a) ? c[a] + 1 : c[a];
      const int span = hi[a] - lo[a];
      grad[a] = span == 0 ? 0.0
                          : (phi[cellIndex(hi[0], hi[1], hi[2])] - phi[cellIndex(lo[0], lo[1], lo[2])]) /
                                (span * g.h);
    }
    return grad;
  }
};

constexpr int kLiquidBit = 8;  // a node's bit beside its three crossing bits

int popcount3(int bits) { return (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1); }

// Each node's crossing mask (which of its +x, +y, +z lattice edges the surface crosses) and
// whether it is liquid; the vertices each slab of nodes will place.
void markCrossings(TaskSystem& tasks, const Lattice& lattice, MarchingCubesWorkspace& workspace) {
  const int nx = lattice.n[0], ny = lattice.n[1], nz = lattice.n[2];
  uint8_t* bits = workspace.nodeBits.data();
  parallelFor(tasks, nz, 1, [&](int64_t begin, int64_t end) {
    for (int64_t K = begin; K < end; ++K) {
      int64_t count = 0;
      for (int J = 0; J < ny; ++J)
        for (int I = 0; I < nx; ++I) {
          const int K32 = static_cast<int>(K), mask = lattice.crossings(I, J, K32);
          bits[lattice.node(I, J, K32)] =
              static_cast<uint8_t>(mask | (isLiquid(lattice.value(I, J, K32)) ? kLiquidBit : 0));
          count += popcount3(mask);
        }
      workspace.slabCount[static_cast<size_t>(K) + 1] = count;
    }
  });
}

// One vertex per crossed edge, at the linear crossing, with the interpolated gradient as its
// normal; each node's first vertex index.
void placeVertices(TaskSystem& tasks, const Lattice& lattice, MarchingCubesWorkspace& workspace, SurfaceMesh* mesh,
                   Array<Eigen::Vector3d>* normals) {
  const int nx = lattice.n[0], ny = lattice.n[1], nz = lattice.n[2];
  const uint8_t* bits = workspace.nodeBits.data();
  parallelFor(tasks, nz, 1, [&](int64_t begin, int64_t end) {
    for (int64_t K64 = begin; K64 < end; ++K64) {
      const int K = static_cast<int>(K64);
      int64_t v = workspace.slabCount[static_cast<size_t>(K)];
      for (int J = 0; J < ny; ++J)
        for (int I = 0; I < nx; ++I) {
          workspace.firstVertex[lattice.node(I, J, K)] = static_cast<int32_t>(v);
          const int mask = bits[lattice.node(I, J, K)] & 7;
          if (mask == 0) continue;
          const double p0 = lattice.value(I, J, K);
          const Eigen::Vector3d x0(lattice.coordinate(0, I), lattice.coordinate(1, J), lattice.coordinate(2, K));
          const Eigen::Vector3d g0 = lattice.gradient(I, J, K);
          for (int a = 0; a < 3; ++a) {
            if (!((mask >> a) & 1)) continue;
            int other[3] = {I, J, K};
            other[a] += 1;
            const double p1 = lattice.value(other[0], other[1], other[2]);
            // One of p0, p1 is < 0 and the other >= 0, so the denominator is nonzero.
            const double t = p0 / (p0 - p1);
            Eigen::Vector3d x = x0;
            x[a] += t * (lattice.coordinate(a, other[a]) - x0[a]);
            const Eigen::Vector3d grad = (1.0 - t) * g0 + t * lattice.gradient(other[0], other[1], other[2]);
            const double length = grad.norm();
            mesh->vertices[static_cast<size_t>(v)] = x;
            (*normals)[static_cast<size_t>(v)] = length > 0.0 ? Eigen::Vector3d(grad / length) : Eigen::Vector3d::Zero();
            ++v;
          }
        }
    }
  });

}

// The triangles of every cube by its liquid corners' case, slab by slab, joined in slab order.
void connectTriangles(TaskSystem& tasks, const Lattice& lattice, const MarchingCubesWorkspace& workspace,
                      Array<std::array<int32_t, 3>>* joined) {
  const int nx = lattice.n[0], ny = lattice.n[1], nz = lattice.n[2];
  const uint8_t* bits = workspace.nodeBits.data();
  const std::array<CaseTriangles, 256>& table = caseTable();
  std::vector<Array<std::array<int32_t, 3>>> slabTriangles(static_cast<size_t>(nz - 1));
  parallelFor(tasks, nz - 1, 1, [&](int64_t begin, int64_t end) {
    for (int64_t K64 = begin; K64 < end; ++K64) {
      const int K = static_cast<int>(K64);
      Array<std::array<int32_t, 3>>& out = slabTriangles[static_cast<size_t>(K)];
      out.clear();
      for (int J = 0; J + 1 < ny; ++J)
        for (int I = 0; I + 1 < nx; ++I) {
          int cubeCase = 0;
          for (int corner = 0; corner < 8; ++corner)
            if (bits[lattice.node(I + (corner & 1), J + ((corner >> 1) & 1), K + ((corner >> 2) & 1))] & kLiquidBit)
              cubeCase |= 1 << corner;
          if (cubeCase == 0 || cubeCase == 255) continue;
          const CaseTriangles& triangles = table[static_cast<size_t>(cubeCase)];
          for (int t = 0; t < triangles.count; ++t) {
            std::array<int32_t, 3> tri;
            for (int s = 0; s < 3; ++s) {
              const int e = triangles.edges[t][s], a = e / 4, u = e & 1, w = (e >> 1) & 1;
              int at[3] = {I, J, K};
              at[a == 0 ? 1 : 0] += u;
              at[a == 2 ? 1 : 2] += w;
              const int lowerAxes = bits[lattice.node(at[0], at[1], at[2])] & ((1 << a) - 1);
              tri[s] = workspace.firstVertex[lattice.node(at[0], at[1], at[2])] + popcount3(lowerAxes);
            }
            out.push_back(tri);
          }
        }
    }
  });
  joined->clear();
  for (const auto& slab : slabTriangles) joined->insert(joined->end(), slab.begin(), slab.end());
}

}  // namespace

Status extractLiquidSurface(TaskSystem& tasks, const MacGridSpec& grid, const double* phi, SurfaceMesh* mesh,
                            Array<Eigen::Vector3d>* normals, MarchingCubesWorkspace& workspace) {
  if (phi == nullptr || mesh == nullptr || normals == nullptr)
    return fail(Status::InvalidArgument, "marching cubes: phi, mesh and normals must not be null");
  if (grid.nx <= 0 || grid.ny <= 0 || grid.nz <= 0 || !(grid.h > 0.0))
    return fail(Status::InvalidArgument, "marching cubes: grid (%d, %d, %d, h %g) is empty", grid.nx, grid.ny,
                grid.nz, grid.h);
  const Lattice lattice(grid, phi);
  const int nx = lattice.n[0], ny = lattice.n[1], nz = lattice.n[2];
  const size_t nodes = static_cast<size_t>(nx) * ny * nz;
  if (nodes > static_cast<size_t>(INT32_MAX / 3))
    return fail(Status::InvalidArgument, "marching cubes: %zu nodes exceed the 32-bit vertex index range", nodes);
  workspace.firstVertex.resize(nodes);
  workspace.nodeBits.resize(nodes);
  workspace.slabCount.assign(static_cast<size_t>(nz) + 1, 0);

  markCrossings(tasks, lattice, workspace);
  for (int K = 0; K < nz; ++K) workspace.slabCount[K + 1] += workspace.slabCount[K];
  const int64_t vertexCount = workspace.slabCount[static_cast<size_t>(nz)];
  if (vertexCount > INT32_MAX)
    return fail(Status::InvalidArgument, "marching cubes: %lld surface vertices exceed the 32-bit index range",
                static_cast<long long>(vertexCount));
  mesh->vertices.resize(static_cast<size_t>(vertexCount));
  normals->resize(static_cast<size_t>(vertexCount));

  placeVertices(tasks, lattice, workspace, mesh, normals);
  connectTriangles(tasks, lattice, workspace, &mesh->triangles);
  return Status::Ok;
}

}  // namespace vp
