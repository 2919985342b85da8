#include "geometry/surface_mesh.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <fstream>

namespace vp {
namespace {

void appendNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, SurfaceMesh& mesh) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& src = *scene.mMeshes[node.mMeshes[m]];
    const int32_t base = static_cast<int32_t>(mesh.vertices.size());
    for (unsigned v = 0; v < src.mNumVertices; ++v) {
      aiVector3D p = transform * src.mVertices[v];
      mesh.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < src.mNumFaces; ++f) {
      const aiFace& face = src.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines survive triangulation
      mesh.triangles.push_back({base + static_cast<int32_t>(face.mIndices[0]),
                                base + static_cast<int32_t>(face.mIndices[1]),
                                base + static_cast<int32_t>(face.mIndices[2])});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) appendNode(scene, *node.mChildren[c], transform, mesh);
}

}  // namespace

Status loadSurfaceMesh(const std::string& path, SurfaceMesh* out) {
  if (!std::ifstream(path).good()) return fail(Status::IoError, "cannot open mesh file '%s'", path.c_str());
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode)
    return fail(Status::ParseError, "mesh file '%s': %s", path.c_str(), importer.GetErrorString());
  SurfaceMesh mesh;
  appendNode(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
  if (mesh.triangles.empty()) return fail(Status::ParseError, "mesh file '%s' contains no triangles", path.c_str());
  for (const Vec3& v : mesh.vertices)
    if (!v.allFinite()) return fail(Status::ParseError, "mesh file '%s' has a non-finite vertex", path.c_str());
  *out = std::move(mesh);
  return Status::Ok;
}

}  // namespace vp
