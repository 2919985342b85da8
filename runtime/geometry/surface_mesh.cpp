#include "geometry/surface_mesh.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <new>

#include "core/regular_file.h"
#include "geometry/isolated_import.h"

namespace vp {
namespace {

void appendNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, SurfaceMesh& out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const size_t base = out.vertices.size();
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines survive aiProcess_Triangulate
      out.triangles.push_back({{static_cast<int32_t>(base + face.mIndices[0]),
                                static_cast<int32_t>(base + face.mIndices[1]),
                                static_cast<int32_t>(base + face.mIndices[2])}});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) appendNode(scene, *node.mChildren[c], transform, out);
}

}  // namespace

Status loadSurfaceMesh(const std::string& path, SurfaceMesh* out) {
  if (out == nullptr) return fail(Status::InvalidArgument, "loadSurfaceMesh: out is null");
  // Checked here because assimp's message for a missing file does not say IoError.
  VP_TRY(checkRegularFile(path));
  if (!std::ifstream(path).good()) return fail(Status::IoError, "file '%s': cannot be opened", path.c_str());
  return importIsolated(path, &importSurfaceMeshWithAssimp, ImportLimits{}, out);
}

Status importSurfaceMeshWithAssimp(const std::string& path, SurfaceMesh* out) {
  try {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (scene == nullptr || scene->mRootNode == nullptr)
      return fail(Status::ParseError, "file '%s': assimp could not import it: %s", path.c_str(),
                  importer.GetErrorString());
    SurfaceMesh mesh;
    appendNode(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
    if (mesh.triangles.empty())
      return fail(Status::ParseError, "file '%s': the scene has no triangles (%u meshes)", path.c_str(),
                  scene->mNumMeshes);
    if (mesh.vertices.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
      return fail(Status::ParseError, "file '%s': %zu vertices exceed the int32 index range", path.c_str(),
                  mesh.vertices.size());
    for (size_t v = 0; v < mesh.vertices.size(); ++v)
      if (!mesh.vertices[v].allFinite())
        return fail(Status::ParseError, "file '%s': vertex %zu (after merging meshes) has a non-finite coordinate",
                    path.c_str(), v);
    *out = std::move(mesh);
    return Status::Ok;
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "file '%s': out of memory", path.c_str());
  } catch (const std::exception& e) {
    return fail(Status::ParseError, "file '%s': %s", path.c_str(), e.what());
  }
}

Status writeSurfaceMeshObj(const SurfaceMesh& mesh, const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return fail(Status::IoError, "file '%s': cannot be created", path.c_str());
  for (const auto& v : mesh.vertices) std::fprintf(file, "v %.17g %.17g %.17g\n", v.x(), v.y(), v.z());
  for (const auto& t : mesh.triangles) std::fprintf(file, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
  const bool ok = std::ferror(file) == 0;
  if (std::fclose(file) != 0 || !ok) return fail(Status::IoError, "file '%s': write failed", path.c_str());
  return Status::Ok;
}

}  // namespace vp
