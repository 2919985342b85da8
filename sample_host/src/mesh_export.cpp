#include "mesh_export.h"

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <cstdio>
#include <cstring>
#include <memory>

namespace {

aiVector3D rotate(const vpQuat& q, const aiVector3D& v) {
  const aiQuaternion aq(q.w, q.x, q.y, q.z);
  return aq.Rotate(v);
}

// One mesh, one default material, one root node: the smallest scene every exporter accepts
// (several dereference mMaterials and mRootNode unconditionally).
std::unique_ptr<aiScene> makeScene(const ViewMesh& m) {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode();
  scene->mRootNode->mName = aiString(m.name);
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned int[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  auto* mesh = new aiMesh();
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{mesh};
  mesh->mName = aiString(m.name);
  mesh->mMaterialIndex = 0;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = static_cast<unsigned>(m.vertexCount);
  mesh->mVertices = new aiVector3D[mesh->mNumVertices];
  mesh->mNormals = new aiVector3D[mesh->mNumVertices];
  for (int32_t i = 0; i < m.vertexCount; ++i) {
    const float* p = &m.positions[3 * i];
    const float* n = &m.normals[3 * i];
    mesh->mVertices[i] = rotate(m.pose.rotation, aiVector3D(p[0], p[1], p[2])) +
                         aiVector3D(m.pose.position.x, m.pose.position.y, m.pose.position.z);
    mesh->mNormals[i] = rotate(m.pose.rotation, aiVector3D(n[0], n[1], n[2]));
  }
  mesh->mNumFaces = static_cast<unsigned>(m.triangleCount);
  mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (int32_t t = 0; t < m.triangleCount; ++t) {
    aiFace& f = mesh->mFaces[t];
    f.mNumIndices = 3;
    f.mIndices = new unsigned int[3];
    for (int k = 0; k < 3; ++k) f.mIndices[k] = static_cast<unsigned>(m.triangles[3 * t + k]);
  }
  return scene;
}

}  // namespace

extern "C" int meshExportFormatKnown(const char* format) {
  Assimp::Exporter exporter;
  for (size_t i = 0; i < exporter.GetExportFormatCount(); ++i)
    if (std::strcmp(exporter.GetExportFormatDescription(i)->id, format) == 0) return 1;
  return 0;
}

extern "C" int meshExportWrite(const ViewMesh* mesh, const char* format, const char* path) {
  if (mesh->triangleCount <= 0) return 1;  // nothing to write (an empty surface this frame)
  const std::unique_ptr<aiScene> scene = makeScene(*mesh);
  Assimp::Exporter exporter;
  if (exporter.Export(scene.get(), format, path) != aiReturn_SUCCESS) {
    std::fprintf(stderr, "mesh export: cannot write '%s' as %s: %s\n", path, format, exporter.GetErrorString());
    return 0;
  }
  return 1;
}
