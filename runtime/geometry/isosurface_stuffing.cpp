#include "geometry/isosurface_stuffing.h"

#include "geometry/bcc_lattice.h"
#include "geometry/graded_bcc_lattice.h"
#include "geometry/row_parity_inside.h"
#include "geometry/segment_surface_crossing.h"
#include "geometry/stuffing_offset.h"
#include "geometry/stuffing_stencils.h"
#include "geometry/stuffing_warp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vp {
namespace {

constexpr const char* kCaller = "tetrahedralizeByStuffing";

uint64_t edgeKey(int64_t a, int64_t b) {
  return a < b ? (uint64_t(a) << 32) | uint64_t(b) : (uint64_t(b) << 32) | uint64_t(a);
}

SampleGrid latticeSamples(const BccLattice& lattice, bool centres) {
  SampleGrid g;
  g.origin = lattice.origin();
  g.spacing = lattice.spacing();
  g.offset = centres ? 0.5 : 0.0;
  for (int k = 0; k < 3; ++k) g.count[k] = lattice.cubes()[k] + (centres ? 0 : 1);
  return g;
}

// +1 inside, -1 outside, for every lattice vertex (its id's order: corners, then centres).
Status classifyLattice(const SurfaceMesh& surface, const BccLattice& lattice, Array<int8_t>* sign) {
  Array<uint8_t> corners, centres;
  VP_TRY(insideByRowParity(surface, latticeSamples(lattice, false), kCaller, &corners));
  VP_TRY(insideByRowParity(surface, latticeSamples(lattice, true), kCaller, &centres));
  sign->resize(corners.size() + centres.size());
  for (size_t i = 0; i < corners.size(); ++i) (*sign)[i] = corners[i] ? 1 : -1;
  for (size_t i = 0; i < centres.size(); ++i) (*sign)[corners.size() + i] = centres[i] ? 1 : -1;
  return Status::Ok;
}

// One cut point per edge from an inside to an outside vertex, in the order of the inside
// vertex's id and then of its neighbours.
std::vector<CutPoint> findCutPoints(const SurfaceMesh& surface, const RefitBvh& bvh, const BccLattice& lattice,
                                    const Array<int8_t>& sign, int64_t* missed) {
  std::vector<CutPoint> cuts;
  for (int64_t id = 0; id < lattice.vertexCount(); ++id) {
    if (sign[static_cast<size_t>(id)] <= 0) continue;
    const LatticePoint p = lattice.point(id);
    const Eigen::Vector3d a = lattice.position(p);
    lattice.forEachNeighbour(p, [&](int64_t n, const LatticePoint& q) {
      if (sign[static_cast<size_t>(n)] > 0) return;
      const Eigen::Vector3d b = lattice.position(q);
      CutPoint cut{id, n, 0.5, Eigen::Vector3d::Zero()};
      // An edge in a surface triangle's plane lies on the surface: any point of it will do.
      if (!firstSurfaceCrossing(bvh, surface, a, b, &cut.t)) ++*missed;
      cut.position = a + cut.t * (b - a);
      cuts.push_back(cut);
    });
  }
  return cuts;
}

// The lattice after the warp, with output vertices numbered: lattice vertices that are not
// outside in lattice order, then the cut points whose edge has no warped end.
struct Stuffing {
  Array<int8_t> sign;                             // +1, 0 (warped), -1 per lattice vertex
  Array<int32_t> output;                          // output vertex per lattice vertex, or -1
  std::unordered_map<uint64_t, int32_t> cutVertex;  // edge key -> output vertex
  Array<Eigen::Vector3d> positions;
  Array<uint8_t> onSurface;                       // per output vertex: a warped vertex or a cut point
};

Status numberVertices(const BccLattice& lattice, const std::vector<CutPoint>& cuts,
                      const std::unordered_map<int64_t, int32_t>& warp, Stuffing* s) {
  for (const auto& [vertex, cut] : warp) s->sign[static_cast<size_t>(vertex)] = 0;
  s->output.assign(s->sign.size(), -1);
  for (int64_t id = 0; id < lattice.vertexCount(); ++id) {
    const int8_t sign = s->sign[static_cast<size_t>(id)];
    if (sign < 0) continue;
    s->output[static_cast<size_t>(id)] = static_cast<int32_t>(s->positions.size());
    s->positions.push_back(sign > 0 ? lattice.position(id) : cuts[static_cast<size_t>(warp.at(id))].position);
    s->onSurface.push_back(sign == 0);
  }
  for (const CutPoint& c : cuts) {
    if (s->sign[static_cast<size_t>(c.inside)] <= 0 || s->sign[static_cast<size_t>(c.outside)] == 0) continue;
    s->cutVertex.emplace(edgeKey(c.inside, c.outside), static_cast<int32_t>(s->positions.size()));
    s->positions.push_back(c.position);
    s->onSurface.push_back(1);
  }
  if (s->positions.size() > size_t(std::numeric_limits<int32_t>::max()))
    return fail(Status::InvalidArgument, "%s: %zu vertices do not fit 32-bit indices", kCaller, s->positions.size());
  return Status::Ok;
}

// The stencil input for one lattice tet; false when no vertex is inside (nothing to fill: a tet
// with only 0 and - vertices lies outside or on the surface, and one with four 0 vertices, which
// the warp may have flattened, is left out too).
bool stencilFor(const BccLattice& lattice, const Stuffing& s, const std::array<LatticePoint, 4>& p, StencilTet* tet,
                std::array<int64_t, 4>* ids) {
  bool any = false;
  for (int k = 0; k < 4; ++k) {
    (*ids)[k] = lattice.id(p[k]);
    tet->lattice[k] = p[k];
    tet->sign[k] = s.sign[static_cast<size_t>((*ids)[k])];
    tet->vertex[k] = s.output[static_cast<size_t>((*ids)[k])];
    any = any || tet->sign[k] > 0;
  }
  return any;
}

// Fills one lattice tet by its stencil.
Status fillOne(const BccLattice& lattice, const Stuffing& s, const std::array<LatticePoint, 4>& p,
               Array<std::array<int32_t, 4>>* tets) {
  StencilTet tet;
  std::array<int64_t, 4> ids{};
  if (!stencilFor(lattice, s, p, &tet, &ids)) return Status::Ok;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (tet.sign[i] > 0 && tet.sign[j] < 0) tet.cut[i][j] = s.cutVertex.at(edgeKey(ids[i], ids[j]));
  if (!fillStencil(tet, s.positions, tets))
    return fail(Status::Internal, "%s: a stencil's prism has cyclic diagonals", kCaller);
  return Status::Ok;
}

Status fillLattice(const BccLattice& lattice, const Stuffing& s,
                   Array<std::array<int32_t, 4>>* tets) {
  Status status = Status::Ok;
  lattice.forEachTet([&](const std::array<LatticePoint, 4>& p) {
    if (ok(status)) status = fillOne(lattice, s, p, tets);
  });
  return status;
}

// The graded lattice: the finest faces by the stencils, the rest (all inside, none warped:
// graded_bcc_lattice.h) as they are, oriented.
Status fillGraded(const BccLattice& lattice, const Stuffing& s, int grading, Array<std::array<int32_t, 4>>* tets) {
  const GradedBccLattice graded(lattice, s.sign, grading);
  Status status = Status::Ok;
  graded.forEachFineTet([&](const std::array<LatticePoint, 4>& p) {
    if (ok(status)) status = fillOne(lattice, s, p, tets);
  });
  graded.forEachCoarseTet([&](const std::array<LatticePoint, 4>& p) {
    if (!ok(status)) return;
    std::array<int32_t, 4> t{};
    for (int k = 0; k < 4; ++k) {
      const int64_t id = lattice.id(p[k]);
      if (id < 0 || s.sign[static_cast<size_t>(id)] <= 0) {
        status = fail(Status::Internal, "%s: a coarse tet has a vertex that is not inside", kCaller);
        return;
      }
      t[k] = s.output[static_cast<size_t>(id)];
    }
    const auto& x = s.positions;
    const Eigen::Vector3d a = x[size_t(t[0])];
    if ((x[size_t(t[1])] - a).cross(x[size_t(t[2])] - a).dot(x[size_t(t[3])] - a) < 0.0) std::swap(t[2], t[3]);
    tets->push_back(t);
  });
  return status;
}

// Drops the warped vertices no tet uses, keeping the order of the others (and their flags).
void compact(Array<Eigen::Vector3d>&& positions, const Array<uint8_t>& flags, Array<std::array<int32_t, 4>>&& tets,
             TetMesh* mesh, Array<uint8_t>* keptFlags) {
  Array<int32_t> renumber(positions.size(), -1);
  for (const auto& t : tets)
    for (int32_t v : t) renumber[static_cast<size_t>(v)] = 0;
  for (size_t v = 0; v < positions.size(); ++v) {
    if (renumber[v] < 0) continue;
    renumber[v] = static_cast<int32_t>(mesh->vertices.size());
    mesh->vertices.push_back(positions[v]);
    keptFlags->push_back(flags[v]);
  }
  for (auto& t : tets)
    for (int32_t& v : t) v = renumber[static_cast<size_t>(v)];
  mesh->tets = std::move(tets);
}

Status build(const SurfaceMesh& surface, int resolution, StuffingBoundary boundary, int grading, TetMesh* out,
             StuffingReport* reportOut) {
  if (grading < 0 || grading > kMaxStuffingGrading)
    return fail(Status::InvalidArgument, "%s: grading %d is outside [0, %d]", kCaller, grading, kMaxStuffingGrading);
  StuffingReport report;
  VP_TRY(makeSurfaceGrid(surface, resolution, kCaller, &report.grid));
  const double h = report.grid.cellSize;
  // One cube of margin on every side: the lattice's outermost vertices are then outside.
  std::array<int64_t, 3> cubes{};
  for (int k = 0; k < 3; ++k) cubes[k] = int64_t(report.grid.cells[k]) + 2;
  const BccLattice lattice(report.grid.origin - Eigen::Vector3d::Constant(h), h, cubes);

  Stuffing s;
  VP_TRY(classifyLattice(surface, lattice, &s.sign));
  for (int8_t sign : s.sign) report.insideVertices += sign > 0;
  RefitBvh bvh;
  bvh.rebuild(surface.vertices, surface.triangles);
  const std::vector<CutPoint> cuts = findCutPoints(surface, bvh, lattice, s.sign, &report.missedCuts);
  const std::unordered_map<int64_t, int32_t> warp = warpLattice(lattice, cuts);
  report.warpedVertices = static_cast<int64_t>(warp.size());
  VP_TRY(numberVertices(lattice, cuts, warp, &s));
  report.cutPoints = static_cast<int64_t>(s.cutVertex.size());

  Array<std::array<int32_t, 4>> tets;
  if (grading == 0) {
    VP_TRY(fillLattice(lattice, s, &tets));
  } else {
    VP_TRY(fillGraded(lattice, s, grading, &tets));
  }
  TetMesh mesh;
  Array<uint8_t> onSurface;
  compact(std::move(s.positions), s.onSurface, std::move(tets), &mesh, &onSurface);
  if (boundary == StuffingBoundary::KeepVolume) offsetStuffedBoundary(surface, bvh, h, onSurface, &mesh, &report.offset);
  *out = std::move(mesh);
  if (reportOut != nullptr) *reportOut = report;
  return Status::Ok;
}

}  // namespace

Status tetrahedralizeByStuffing(const SurfaceMesh& surface, int resolution, TetMesh* out, StuffingReport* report,
                                StuffingBoundary boundary, int grading) {
  if (out == nullptr) return fail(Status::InvalidArgument, "%s: out is null", kCaller);
  try {
    return build(surface, resolution, boundary, grading, out, report);
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "%s: out of memory at resolution %d", kCaller, resolution);
  }
}

}  // namespace vp
