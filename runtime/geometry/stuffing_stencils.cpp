#include "geometry/stuffing_stencils.h"

#include "geometry/tet_mesh.h"

#include <utility>
#include <vector>

namespace vp {
namespace {

using Tet = std::array<int32_t, 4>;

struct Emitter {
  const Array<Eigen::Vector3d>& positions;
  Array<Tet>* out;

  void operator()(Tet t) const {
    if (signedTetVolume(positions[t[0]], positions[t[1]], positions[t[2]], positions[t[3]]) < 0.0)
      std::swap(t[2], t[3]);
    out->push_back(t);
  }
};

// For the face (u, v, w) with u and v inside and w outside, whether the diagonal of its
// quadrilateral (u, v, cut vw, cut uw) touches u (then it is u - cut vw) rather than v.
bool diagonalTouchesFirst(const LatticePoint& u, const LatticePoint& v, const LatticePoint& w) {
  if (BccLattice::isLongEdge(u, v)) {
    const int axis = u[0] != v[0] ? 0 : (u[1] != v[1] ? 1 : 2);
    return (u[axis] / 2) % 2 == 0;
  }
  return !BccLattice::isLongEdge(u, w);
}

// The triangular prism x0 x1 x2 / y0 y1 y2 with lateral edges xi yi. Its quadrilateral i is
// (xi, xi+1, yi+1, yi); fromX[i] says its diagonal is xi - yi+1 (else xi+1 - yi). A vertex
// that both its quadrilaterals' diagonals touch sees the rest of the prism as one tet and one
// pyramid: a cone from it. Returns false when no vertex qualifies (cyclic diagonals).
bool emitPrism(const std::array<int32_t, 3>& x, const std::array<int32_t, 3>& y, const std::array<bool, 3>& fromX,
               const Emitter& emit) {
  for (int i = 0; i < 3; ++i) {
    const int prev = (i + 2) % 3, j = (i + 1) % 3, jn = (i + 2) % 3;
    const bool atX = fromX[i] && !fromX[prev], atY = !fromX[i] && fromX[prev];
    if (!atX && !atY) continue;
    const int32_t apex = atX ? x[i] : y[i];
    const std::array<int32_t, 3>& opposite = atX ? y : x;
    emit({{apex, opposite[0], opposite[1], opposite[2]}});
    // The quadrilateral j = (xj, xjn, yjn, yj), the one without the apex.
    if (fromX[j]) {
      emit({{apex, x[j], x[jn], y[jn]}});
      emit({{apex, x[j], y[jn], y[j]}});
    } else {
      emit({{apex, x[j], x[jn], y[j]}});
      emit({{apex, x[jn], y[jn], y[j]}});
    }
    return true;
  }
  return false;
}

struct Corners {
  std::vector<int> inside, zero, outside;  // local corners 0..3 by sign
};

Corners sortCorners(const StencilTet& tet) {
  Corners c;
  for (int k = 0; k < 4; ++k) (tet.sign[k] > 0 ? c.inside : tet.sign[k] == 0 ? c.zero : c.outside).push_back(k);
  return c;
}

// + a b, 0 z, - m: the pyramid from z over the quadrilateral (a, b, cut bm, cut am).
void emitPyramid(const StencilTet& tet, int a, int b, int z, int m, const Emitter& emit) {
  const int32_t q[4] = {tet.vertex[a], tet.vertex[b], tet.cut[b][m], tet.cut[a][m]};
  const int32_t apex = tet.vertex[z];
  if (diagonalTouchesFirst(tet.lattice[a], tet.lattice[b], tet.lattice[m])) {
    emit({{apex, q[0], q[1], q[2]}});
    emit({{apex, q[0], q[2], q[3]}});
  } else {
    emit({{apex, q[0], q[1], q[3]}});
    emit({{apex, q[1], q[2], q[3]}});
  }
}

// + a b, - m n: the prism (a, cut am, cut an) / (b, cut bm, cut bn).
bool emitTwoTwo(const StencilTet& tet, int a, int b, int m, int n, const Array<Eigen::Vector3d>& positions,
                const Emitter& emit) {
  const std::array<int32_t, 3> x{{tet.vertex[a], tet.cut[a][m], tet.cut[a][n]}};
  const std::array<int32_t, 3> y{{tet.vertex[b], tet.cut[b][m], tet.cut[b][n]}};
  std::array<bool, 3> fromX{};
  fromX[0] = diagonalTouchesFirst(tet.lattice[a], tet.lattice[b], tet.lattice[m]);
  fromX[2] = !diagonalTouchesFirst(tet.lattice[a], tet.lattice[b], tet.lattice[n]);
  if (fromX[0] == fromX[2]) {
    fromX[1] = !fromX[0];
  } else {
    fromX[1] = (positions[x[1]] - positions[y[2]]).squaredNorm() <= (positions[x[2]] - positions[y[1]]).squaredNorm();
  }
  return emitPrism(x, y, fromX, emit);
}

// + a b c, - m: the prism (a, b, c) / (cut am, cut bm, cut cm).
bool emitThreeOne(const StencilTet& tet, const std::vector<int>& p, int m, const Emitter& emit) {
  std::array<int32_t, 3> x{}, y{};
  std::array<bool, 3> fromX{};
  for (int i = 0; i < 3; ++i) {
    x[i] = tet.vertex[p[i]];
    y[i] = tet.cut[p[i]][m];
    fromX[i] = diagonalTouchesFirst(tet.lattice[p[i]], tet.lattice[p[(i + 1) % 3]], tet.lattice[m]);
  }
  return emitPrism(x, y, fromX, emit);
}

}  // namespace

bool fillStencil(const StencilTet& tet, const Array<Eigen::Vector3d>& positions, Array<Tet>* out) {
  const Emitter emit{positions, out};
  const Corners c = sortCorners(tet);
  if (c.inside.empty()) return true;
  if (c.outside.empty()) {
    emit(tet.vertex);
    return true;
  }
  if (c.inside.size() == 1) {  // the + vertex, the 0 vertices and the cut points
    const int a = c.inside[0];
    Tet t{};
    int n = 0;
    t[n++] = tet.vertex[a];
    for (int z : c.zero) t[n++] = tet.vertex[z];
    for (int m : c.outside) t[n++] = tet.cut[a][m];
    emit(t);
    return true;
  }
  if (c.inside.size() == 2 && c.zero.size() == 1) {
    emitPyramid(tet, c.inside[0], c.inside[1], c.zero[0], c.outside[0], emit);
    return true;
  }
  if (c.inside.size() == 2)
    return emitTwoTwo(tet, c.inside[0], c.inside[1], c.outside[0], c.outside[1], positions, emit);
  return emitThreeOne(tet, c.inside, c.outside[0], emit);
}

}  // namespace vp
