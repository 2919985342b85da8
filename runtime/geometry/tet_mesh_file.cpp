#include "geometry/tet_mesh_file.h"

#include "geometry/gmsh_reader.h"
#include "geometry/tetgen_reader.h"
#include "geometry/vtk_reader.h"

#include <cctype>
#include <new>

namespace vp {

Status readTetMeshFile(const std::string& path, TetMesh* out, TetMeshRepairReport* report) {
  if (out == nullptr) return fail(Status::InvalidArgument, "readTetMeshFile: out is null");
  try {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of("/\\");
    std::string ext;
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));

    TetMesh mesh;
    if (ext == ".msh") {
      VP_TRY(readGmsh(path, &mesh));
    } else if (ext == ".node" || ext == ".ele") {
      VP_TRY(readTetGen(path, &mesh));
    } else if (ext == ".vtk") {
      VP_TRY(readVtk(path, &mesh));
    } else {
      return fail(Status::Unsupported,
                  "file '%s': extension '%s' is not a supported tet mesh format (.msh, .node/.ele, .vtk)",
                  path.c_str(), ext.c_str());
    }
    Status status = validateAndRepairTetMesh(mesh, report);
    if (status != Status::Ok) return addErrorContext(status, "file '" + path + "'");
    *out = std::move(mesh);
    return Status::Ok;
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "file '%s': out of memory", path.c_str());
  }
}

}  // namespace vp
