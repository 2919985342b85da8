#include "deform/embedded_render_mesh.h"

#include "core/parallel_for.h"
#include "deform/bb_evaluation.h"
#include "deform/bb_multi_index.h"

namespace vp {

Status EmbeddedRenderMesh::build(const TetMesh& mesh, SurfaceMesh rest) {
  Array<EmbeddedPoint> embedding;
  VP_TRY(embedPoints(mesh, rest.vertices, &embedding));
  embedding_ = std::move(embedding);
  quality_ = tetMeshQuality(mesh, rest);
  rest_ = std::move(rest);
  return Status::Ok;
}

void EmbeddedRenderMesh::update(TaskSystem& tasks, int degree, int nodesPerElement,
                                const Array<int32_t>& elementNodes, const Array<double>& x) {
  positions_.resize(embedding_.size());
  const int N = nodesPerElement;
  parallelFor(tasks, static_cast<int64_t>(embedding_.size()), 2048, [&](int64_t begin, int64_t end) {
    for (int64_t p = begin; p < end; ++p) {
      // The BB polynomial of the element at the point's barycentric coordinates (for degree
      // 1 the plain barycentric combination of the corners).
      const EmbeddedPoint& e = embedding_[p];
      double coeffs[3 * kBBMaxNodes], value[3];
      for (int a = 0; a < N; ++a) {
        const int32_t node = elementNodes[N * static_cast<int64_t>(e.tet) + a];
        for (int k = 0; k < 3; ++k) coeffs[3 * a + k] = x[3 * node + k];
      }
      bbEvaluate(degree, coeffs, e.barycentric.data(), value);
      positions_[p] = Vec3(value[0], value[1], value[2]);
    }
  });
  computeVertexNormals(positions_, rest_.triangles, &normals_);
  ++version_;
}

void EmbeddedRenderMesh::restore(Array<Vec3>&& positions, Array<Vec3>&& normals) {
  positions_ = std::move(positions);
  normals_ = std::move(normals);
  ++version_;
}

const RefitBvh& EmbeddedRenderMesh::bvh() const {
  if (bvhVersion_ == version_) return bvh_;
  if (bvh_.empty()) bvh_.rebuild(positions_, rest_.triangles);
  else bvh_.refit(positions_, rest_.triangles);
  bvhVersion_ = version_;
  return bvh_;
}

}  // namespace vp
