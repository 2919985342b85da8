#include "fluid/solids/mesh_face_classes.h"

#include <algorithm>
#include <cmath>

#include "collide/mesh_grid_inside.h"

namespace vp {

namespace {

// Faces of r whose square the box [lo, hi] (grid units) may touch, marked Touched; the box is
// widened by kSlack cells against the rounding of the grid units.
constexpr double kSlack = 1e-6;

void markTouched(const FaceBox& r, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Array<uint8_t>* classes) {
  int from[3], to[3];
  for (int d = 0; d < 3; ++d) {
    // Axis faces sit at integer coordinates; the others span [j, j + 1].
    const double l = std::ceil(lo[d] - kSlack) - (d == r.axis ? 0.0 : 1.0);
    const double u = std::floor(hi[d] + kSlack);
    from[d] = static_cast<int>(std::max<double>(l, r.lo[d]));
    to[d] = static_cast<int>(std::min<double>(u, r.hi[d]));
    if (from[d] > to[d]) return;
  }
  for (int k = from[2]; k <= to[2]; ++k)
    for (int j = from[1]; j <= to[1]; ++j)
      for (int i = from[0]; i <= to[0]; ++i)
        (*classes)[static_cast<size_t>(r.number(i, j, k))] = static_cast<uint8_t>(FaceClass::Touched);
}

}  // namespace

int64_t classifiedFaces(const FaceFractionField& field, const Aabb& box) {
  int64_t n = 0;
  for (int a = 0; a < 3; ++a) n += facesAround(field, box, a).faces();
  return n;
}

void classifyMeshFaces(const PreparedCollider& mesh, const FaceFractionField& field, const Aabb& box,
                       MeshFaceClasses* out) {
  out->mesh = &mesh;
  const MacGridSpec& g = field.grid;
  for (int a = 0; a < 3; ++a) {
    const FaceBox r = facesAround(field, box, a);
    out->boxes[a] = r;
    out->classes[a].clear();
    if (r.faces() == 0) continue;
    // Face (i, j, k) of axis a has its centre at origin + h (i, j, k) + h/2 across the axis.
    SampleGrid centres;
    centres.spacing = g.h;
    for (int d = 0; d < 3; ++d) {
      centres.origin[d] = g.origin[d] + g.h * (r.lo[d] + (d == a ? 0.0 : 0.5));
      centres.count[static_cast<size_t>(d)] = r.hi[d] - r.lo[d] + 1;
    }
    Array<uint8_t> inside;
    if (meshGridInside(mesh, centres, "classifyMeshFaces", &inside) != Status::Ok) {
      out->classes[a].assign(static_cast<size_t>(r.faces()), static_cast<uint8_t>(FaceClass::Touched));
      continue;
    }
    out->classes[a] = std::move(inside);  // Outside 0, Inside 1, in the box's numbering
    for (const Eigen::Vector3i& t : mesh.triangles) {
      const Eigen::Vector3d& p = mesh.worldVertices[t[0]];
      const Eigen::Vector3d& q = mesh.worldVertices[t[1]];
      const Eigen::Vector3d& s = mesh.worldVertices[t[2]];
      const Eigen::Vector3d lo = (p.cwiseMin(q).cwiseMin(s) - g.origin) / g.h;
      const Eigen::Vector3d hi = (p.cwiseMax(q).cwiseMax(s) - g.origin) / g.h;
      markTouched(r, lo, hi, &out->classes[a]);
    }
  }
}

}  // namespace vp
