#include "geometry/tet_mesh_validation.h"

#include <cmath>
#include <limits>
#include <new>

namespace vp {
namespace {

// Checks everything first and mutates only when all checks passed, so the mesh is
// unchanged on error.
Status check(const TetMesh& mesh) {
  if (mesh.vertices.empty()) return fail(Status::InvalidArgument, "tet mesh: no vertices");
  if (mesh.tets.empty()) return fail(Status::InvalidArgument, "tet mesh: no tets");
  constexpr size_t kMaxCount = static_cast<size_t>(std::numeric_limits<int32_t>::max());
  if (mesh.vertices.size() > kMaxCount || mesh.tets.size() > kMaxCount)
    return fail(Status::InvalidArgument, "tet mesh: %zu vertices / %zu tets exceed the int32 index range",
                mesh.vertices.size(), mesh.tets.size());

  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3d& x = mesh.vertices[v];
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(x[k]))
        return fail(Status::InvalidArgument, "tet mesh: vertex %zu has a non-finite coordinate %c = %g", v,
                    "xyz"[k], x[k]);
  }

  const int64_t numVertices = static_cast<int64_t>(mesh.vertices.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    for (int k = 0; k < 4; ++k) {
      if (tet[k] < 0 || tet[k] >= numVertices)
        return fail(Status::InvalidArgument, "tet mesh: tet %zu corner %d is vertex %d, outside [0, %lld)", t, k,
                    tet[k], static_cast<long long>(numVertices));
      for (int j = 0; j < k; ++j)
        if (tet[j] == tet[k])
          return fail(Status::InvalidArgument, "tet mesh: tet %zu uses vertex %d twice (corners %d and %d)", t,
                      tet[k], j, k);
    }
  }

  const double edge = meanTetEdgeLength(mesh);
  const double minVolume = kDegenerateVolumeTolerance * edge * edge * edge;
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const double volume = signedTetVolume(mesh, t);
    if (!(std::fabs(volume) > minVolume))
      return fail(Status::InvalidArgument,
                  "tet mesh: tet %zu is degenerate: volume %g is below %g (1e-10 x mean edge length %g cubed)", t,
                  volume, minVolume, edge);
  }
  return Status::Ok;
}

}  // namespace

Status validateAndRepairTetMesh(TetMesh& mesh, TetMeshRepairReport* report) {
  try {
    VP_TRY(check(mesh));

    // Compute the repairs into new arrays and commit with a swap, so an allocation failure
    // half way through also leaves the mesh unchanged.
    Array<std::array<int32_t, 4>> tets = mesh.tets;
    int64_t inverted = 0;
    for (size_t t = 0; t < tets.size(); ++t) {
      if (signedTetVolume(mesh, t) < 0.0) {
        std::swap(tets[t][2], tets[t][3]);
        ++inverted;
      }
    }

    Array<int32_t> newIndex(mesh.vertices.size(), -1);
    for (const auto& tet : tets)
      for (int32_t v : tet) newIndex[v] = 0;
    int32_t used = 0;
    for (int32_t& index : newIndex)
      if (index == 0) index = used++;
    const int64_t removed = static_cast<int64_t>(mesh.vertices.size()) - used;

    Array<Eigen::Vector3d> vertices;
    if (removed > 0) {
      vertices.resize(static_cast<size_t>(used));
      for (size_t v = 0; v < mesh.vertices.size(); ++v)
        if (newIndex[v] >= 0) vertices[newIndex[v]] = mesh.vertices[v];
      for (auto& tet : tets)
        for (int32_t& v : tet) v = newIndex[v];
    }

    mesh.tets.swap(tets);
    if (removed > 0) mesh.vertices.swap(vertices);
    if (report != nullptr) {
      report->invertedTetsFixed = inverted;
      report->unusedVerticesRemoved = removed;
      report->newIndexOfOldVertex = std::move(newIndex);
    }
    return Status::Ok;
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "tet mesh: out of memory while validating %zu vertices / %zu tets",
                mesh.vertices.size(), mesh.tets.size());
  }
}

}  // namespace vp
