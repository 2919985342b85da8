// Face open fractions and solid velocities over a MAC grid (layout in face_fraction_field.h).
#include "fluid/solids/face_fraction_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "fluid/grid_index.h"
#include "fluid/solids/cell_box.h"
#include "fluid/solids/face_box.h"
#include "fluid/solids/mesh_face_classes.h"

namespace vp {
namespace {

constexpr int kMaxCollidersPerFace = 64;

Status checkArgs(const PreparedCollider* const* colliders, int count,
                 const FaceFractionField* field) {
  if (field == nullptr) return fail(Status::InvalidArgument, "face fractions: field is null");
  if (count < 0 || (count > 0 && colliders == nullptr))
    return fail(Status::InvalidArgument, "face fractions: colliders null or count %d < 0", count);
  for (int i = 0; i < count; ++i)
    if (colliders[i] == nullptr)
      return fail(Status::InvalidArgument, "face fractions: colliders[%d] is null", i);
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = field->faceDims(a);
    const size_t n = static_cast<size_t>(d.x()) * d.y() * d.z();
    if (field->open[a].size() != n || field->solidVelocity[a].size() != n)
      return fail(Status::InvalidArgument,
                  "face fractions: field arrays of axis %d not sized for the grid "
                  "(call initFaceFractionField)", a);
  }
  return Status::Ok;
}

// Normal velocity of one collider over its covered part of `face` (covered fraction `a`).
double colliderNormalVelocity(const PreparedCollider& c, const AxisFace& face, double a) {
  const ColliderShape& s = c.shape;
  const bool varies = s.angularVelocity.squaredNorm() > 0.0 || !c.vertexVelocities.empty();
  Eigen::Vector3d x = face.centre;
  if (varies && a < 1.0) {
    const int a1 = (face.axis + 1) % 3, a2 = (face.axis + 2) % 3;
    double wsum = 0.0;
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    for (int q = 0; q < 4; ++q) {
      AxisFace sub = face;
      sub.h = 0.5 * face.h;
      sub.centre[a1] += (q & 1 ? 0.25 : -0.25) * face.h;
      sub.centre[a2] += (q & 2 ? 0.25 : -0.25) * face.h;
      const double w = coveredFraction(c, sub);
      wsum += w;
      acc += w * sub.centre;
    }
    if (wsum > 0.0) x = acc / wsum;
  }
  return solidVelocityAt(c, x)[face.axis];
}

// A face that one deforming surface covers whole gets its velocity in a second pass
// (settleInteriorFaces), once its neighbours' coverage is known; until then it holds this.
constexpr double kVelocityPending = std::numeric_limits<double>::quiet_NaN();

bool deforming(const PreparedCollider& c) { return !c.vertexVelocities.empty(); }

// The meshes' face classes of the box being recomputed (mesh_face_classes.h).
using MeshClassList = std::vector<MeshFaceClasses>;

// A mesh's class of a face where its classes decide (Touched where they do not, or where the
// mesh was not classified).
FaceClass classOf(const PreparedCollider& c, int axis, int i, int j, int k, const MeshClassList& classes) {
  for (const MeshFaceClasses& m : classes)
    if (m.mesh == &c) return m.at(axis, i, j, k);
  return FaceClass::Touched;
}

// One collider's coverage of a face (from its classes where they decide, else exact) and the
// solid's normal velocity over the covered part: a deforming surface's where it crosses the
// face (coveredFractionAndTraceVelocity; a face it covers whole is left pending), another
// mesh's at the covered part's exact centroid, any other shape's as colliderNormalVelocity
// finds it.
void coverFace(const PreparedCollider& c, const AxisFace& face, int i, int j, int k, const MeshClassList& classes,
               double* covered, double* velocity) {
  const FaceClass cls = classOf(c, face.axis, i, j, k, classes);
  Eigen::Vector3d centroid = face.centre, traceVelocity;
  bool traced = false;
  if (cls != FaceClass::Touched) *covered = cls == FaceClass::Inside ? 1.0 : 0.0;
  else if (deforming(c)) *covered = coveredFractionAndTraceVelocity(c, face, &traceVelocity, &traced);
  else *covered = coveredFractionAndCentroid(c, face, &centroid);
  *velocity = 0.0;
  if (!(*covered > 0.0)) return;
  if (deforming(c) && *covered >= 1.0) *velocity = kVelocityPending;
  else if (deforming(c)) *velocity = traced ? traceVelocity[face.axis] : solidVelocityAt(c, face.centre)[face.axis];
  else if (c.shape.kind == ShapeKind::TriangleMesh) *velocity = solidVelocityAt(c, centroid)[face.axis];
  else *velocity = colliderNormalVelocity(c, face, *covered);
}

void recomputeFace(const PreparedCollider* const* colliders, int count, const MeshClassList& classes, int axis,
                   int i, int j, int k, FaceFractionField* field) {
  const AxisFace face = field->face(axis, i, j, k);
  const Aabb fb = faceBounds(face);
  const PreparedCollider* near[kMaxCollidersPerFace];
  int n = 0;
  for (int c = 0; c < count && n < kMaxCollidersPerFace; ++c)
    if (colliders[c]->bounds.overlaps(fb)) near[n++] = colliders[c];
  double covered = 0.0, velocity = 0.0;
  if (n == 1) {
    coverFace(*near[0], face, i, j, k, classes, &covered, &velocity);
  } else if (n > 1) {
    covered = coveredFractionUnion(near, n, face);
    if (covered > 0.0) {
      double wsum = 0.0, vsum = 0.0;
      for (int c = 0; c < n; ++c) {
        const double ac = coveredFraction(*near[c], face);
        if (ac > 0.0) {
          wsum += ac;
          vsum += ac * colliderNormalVelocity(*near[c], face, ac);
        }
      }
      velocity = wsum > 0.0 ? vsum / wsum : 0.0;
    }
  }
  const size_t f = field->faceIndex(axis, i, j, k);
  field->open[axis][f] = 1.0 - covered;
  field->solidVelocity[axis][f] = velocity;
}

// Recomputing a face costs at least this many of the samples that bound a slice (an
// advection sample): a coverage evaluation per collider near it. Traced in the frame-budget
// benchmark around the default scene's moving colliders, faces beside a collider cost about
// this much and faces on it several times more; the slab sizer corrects for the rest.
constexpr int64_t kSamplesPerFace = 256;
// Faces per parallel chunk: a face near a collider costs far more than one away from it, so
// chunks are small.
constexpr int64_t kFaceGrain = 4;
// Settling a face is a check of its two cells, and for the faces beside fluid a
// nearest-point search: a few coverage samples' worth on average.
constexpr int64_t kSamplesPerSettledFace = 16;
constexpr int64_t kSettleGrain = 64;
// Classifying the faces of a box against a mesh (mesh_face_classes.h) is a pass over its
// triangles and its rows of faces: a sample's worth per face.
constexpr int64_t kSamplesPerClassifiedFace = 1;

void recomputeFaces(const PreparedCollider* const* colliders, int count, const MeshClassList& classes,
                    const FaceBox& r, int64_t begin, int64_t end, FaceFractionField* field) {
  forEachFaceOf(r, begin, end,
                [&](int i, int j, int k) { recomputeFace(colliders, count, classes, r.axis, i, j, k, field); });
}

// A mesh is classified over a box when the box has at least as many faces as the mesh has
// triangles: the classification visits every triangle once, the exact path a column of them
// per face (a large static mesh beside a small moving collider is left to the exact path).
bool worthClassifying(const PreparedCollider& c, const Aabb& box, int64_t faces) {
  return c.shape.kind == ShapeKind::TriangleMesh && c.bounds.overlaps(box) &&
         faces >= static_cast<int64_t>(c.triangles.size());
}

void classifyMeshes(const PreparedCollider* const* colliders, int count, const Aabb& box,
                    const FaceFractionField& field, MeshClassList* classes) {
  const int64_t faces = classifiedFaces(field, box);
  classes->clear();
  for (int c = 0; c < count; ++c) {
    if (!worthClassifying(*colliders[c], box, faces)) continue;
    classes->emplace_back();
    classifyMeshFaces(*colliders[c], field, box, &classes->back());
  }
}

// Whether any face of cell (i, j, k) is open at all (so the cell may be fluid); false for a
// cell outside the grid.
bool cellHasOpenFace(const FaceFractionField& f, int i, int j, int k) {
  const MacGridSpec& g = f.grid;
  if (i < 0 || j < 0 || k < 0 || i >= g.nx || j >= g.ny || k >= g.nz) return false;
  return cellOpenSum(f, i, j, k) > 0.0;
}

// The pending faces of [begin, end) of r: the nearest surface point's velocity when a cell
// beside the face has an open face, else the surface's mean vertex velocity.
void settleInteriorFaces(const PreparedCollider* const* colliders, int count, const FaceBox& r, int64_t begin,
                         int64_t end, FaceFractionField* field) {
  forEachFaceOf(r, begin, end, [&](int i, int j, int k) {
    double& velocity = field->solidVelocity[r.axis][field->faceIndex(r.axis, i, j, k)];
    if (!std::isnan(velocity)) return;
    const AxisFace face = field->face(r.axis, i, j, k);
    const Aabb fb = faceBounds(face);
    const PreparedCollider* surface = nullptr;
    for (int c = 0; c < count && surface == nullptr; ++c)
      if (colliders[c]->bounds.overlaps(fb)) surface = colliders[c];
    Eigen::Vector3i low(i, j, k);
    low[r.axis] -= 1;
    const bool read = cellHasOpenFace(*field, i, j, k) || cellHasOpenFace(*field, low.x(), low.y(), low.z());
    velocity = read ? colliderNormalVelocity(*surface, face, 1.0) : surface->meanVertexVelocity[r.axis];
  });
}

void recomputeBox(const PreparedCollider* const* colliders, int count, const Aabb& box,
                  FaceFractionField* field) {
  MeshClassList classes;
  classifyMeshes(colliders, count, box, *field, &classes);
  for (int a = 0; a < 3; ++a) {
    const FaceBox r = facesAround(*field, box, a);
    recomputeFaces(colliders, count, classes, r, 0, r.faces(), field);
  }
  for (int a = 0; a < 3; ++a) {
    const FaceBox r = facesAround(*field, box, a);
    settleInteriorFaces(colliders, count, r, 0, r.faces(), field);
  }
}

// Faces, not rows, are the unit: one row of faces along a collider can cost a whole slice.
void addBoxPasses(SlabPasses& passes, const PreparedCollider* const* colliders, int count, const Aabb& box,
                  FaceFractionField* field) {
  auto classes = std::make_shared<MeshClassList>();
  passes.addWhole(classifiedFaces(*field, box) * kSamplesPerClassifiedFace,
                  [=] { classifyMeshes(colliders, count, box, *field, classes.get()); });
  for (int a = 0; a < 3; ++a) {
    const FaceBox r = facesAround(*field, box, a);
    passes.addParallel(r.faces(), kSamplesPerFace, kFaceGrain, [=](int64_t begin, int64_t end) {
      recomputeFaces(colliders, count, *classes, r, begin, end, field);
    });
  }
  for (int a = 0; a < 3; ++a) {
    const FaceBox r = facesAround(*field, box, a);
    passes.addParallel(r.faces(), kSamplesPerSettledFace, kSettleGrain, [=](int64_t begin, int64_t end) {
      settleInteriorFaces(colliders, count, r, begin, end, field);
    });
  }
}

void openAllFaces(FaceFractionField* field) {
  for (int a = 0; a < 3; ++a) {
    std::fill(field->open[a].begin(), field->open[a].end(), 1.0);
    std::fill(field->solidVelocity[a].begin(), field->solidVelocity[a].end(), 0.0);
  }
}

}  // namespace

Eigen::Vector3i FaceFractionField::faceDims(int axis) const {
  return Eigen::Vector3i(grid.nx + (axis == 0), grid.ny + (axis == 1), grid.nz + (axis == 2));
}

size_t FaceFractionField::faceIndex(int axis, int i, int j, int k) const {
  const Eigen::Vector3i d = faceDims(axis);
  return static_cast<size_t>(i) + static_cast<size_t>(d.x()) * (j + static_cast<size_t>(d.y()) * k);
}

AxisFace FaceFractionField::face(int axis, int i, int j, int k) const {
  AxisFace f;
  f.axis = axis;
  f.h = grid.h;
  Eigen::Vector3d c(i + 0.5, j + 0.5, k + 0.5);
  c[axis] -= 0.5;
  f.centre = grid.origin + grid.h * c;
  return f;
}

Status initFaceFractionField(const MacGridSpec& grid, FaceFractionField* field) {
  if (field == nullptr) return fail(Status::InvalidArgument, "initFaceFractionField: field is null");
  if (!grid.origin.allFinite())
    return fail(Status::InvalidArgument, "MacGridSpec.origin is not finite");
  if (!std::isfinite(grid.h) || !(grid.h > 0.0))
    return fail(Status::InvalidArgument, "MacGridSpec.h must be > 0, got %g", grid.h);
  if (grid.nx <= 0 || grid.ny <= 0 || grid.nz <= 0)
    return fail(Status::InvalidArgument, "MacGridSpec nx, ny, nz must be > 0, got %d, %d, %d",
                grid.nx, grid.ny, grid.nz);
  const double cells = static_cast<double>(grid.nx + 1) * (grid.ny + 1) * (grid.nz + 1);
  if (cells > 2e9)
    return fail(Status::InvalidArgument, "MacGridSpec: %d x %d x %d cells is too large",
                grid.nx, grid.ny, grid.nz);
  field->grid = grid;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = field->faceDims(a);
    const size_t n = static_cast<size_t>(d.x()) * d.y() * d.z();
    field->open[a].assign(n, 1.0);
    field->solidVelocity[a].assign(n, 0.0);
  }
  return Status::Ok;
}

Status computeFaceFractions(const PreparedCollider* const* colliders, int count,
                            FaceFractionField* field) {
  VP_TRY(checkArgs(colliders, count, field));
  openAllFaces(field);
  for (int c = 0; c < count; ++c) recomputeBox(colliders, count, colliders[c]->bounds, field);
  return Status::Ok;
}

std::array<Aabb, 2> boxesToUpdate(const Aabb& oldBounds, const Aabb& newBounds) {
  if (!oldBounds.overlaps(newBounds)) return {oldBounds, newBounds};
  Aabb both;
  both.lo = oldBounds.lo.cwiseMin(newBounds.lo);
  both.hi = oldBounds.hi.cwiseMax(newBounds.hi);
  return {both, Aabb{}};
}

Status updateFaceFractions(const PreparedCollider* const* colliders, int count,
                           const Aabb& oldBounds, const Aabb& newBounds,
                           FaceFractionField* field) {
  VP_TRY(checkArgs(colliders, count, field));
  for (const Aabb& box : boxesToUpdate(oldBounds, newBounds)) recomputeBox(colliders, count, box, field);
  return Status::Ok;
}

Status addFaceFractionPasses(SlabPasses& passes, const PreparedCollider* const* colliders, int count,
                             FaceFractionField* field) {
  VP_TRY(checkArgs(colliders, count, field));
  for (int a = 0; a < 3; ++a)
    passes.addParallel(static_cast<int64_t>(field->open[a].size()), 1, 4096, [field, a](int64_t begin, int64_t end) {
      std::fill(field->open[a].begin() + begin, field->open[a].begin() + end, 1.0);
      std::fill(field->solidVelocity[a].begin() + begin, field->solidVelocity[a].begin() + end, 0.0);
    });
  for (int c = 0; c < count; ++c) addBoxPasses(passes, colliders, count, colliders[c]->bounds, field);
  return Status::Ok;
}

Status addFaceFractionUpdatePasses(SlabPasses& passes, const PreparedCollider* const* colliders, int count,
                                   const Aabb& oldBounds, const Aabb& newBounds, FaceFractionField* field) {
  VP_TRY(checkArgs(colliders, count, field));
  for (const Aabb& box : boxesToUpdate(oldBounds, newBounds)) addBoxPasses(passes, colliders, count, box, field);
  return Status::Ok;
}

}  // namespace vp
