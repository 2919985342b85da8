// Hand-written because assimp reads surface meshes only (see text_scanner.h).
// Format reference: https://wias-berlin.de/software/tetgen/fformats.html
#include "geometry/tetgen_reader.h"

#include "geometry/text_scanner.h"

#include <new>
#include <string_view>

namespace vp {
namespace {

bool endsWith(const std::string& s, const char* suffix) {
  std::string_view tail(suffix);
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

Status expectNoMoreRecords(TextScanner& s, int64_t count) {
  std::string_view token;
  if (s.next(&token))
    return s.error("expected end of file after the %lld records declared in the header, got '%s'",
                   static_cast<long long>(count), TextScanner::quote(token).c_str());
  return Status::Ok;
}

Status readNodeFile(TextScanner& s, TetMesh* mesh, int64_t* base) {
  int64_t count = 0, dim = 0, numAttributes = 0, numMarkers = 0;
  VP_TRY(s.readInt("number of points", &count));
  VP_TRY(s.readIntOnLine("dimension", &dim));
  VP_TRY(s.readIntOnLine("number of attributes", &numAttributes));
  VP_TRY(s.readIntOnLine("number of boundary markers (0 or 1)", &numMarkers));
  VP_TRY(s.expectEndOfLine("the .node header"));
  if (count == 0)
    return s.error("0 points: the points are in a .poly/.smesh file, which is not supported");
  VP_TRY(s.checkCount(count, 8, "number of points"));
  if (dim != 3) return s.error("dimension must be 3, got %lld", static_cast<long long>(dim));
  if (numAttributes < 0 || numAttributes > 1000)
    return s.error("number of attributes must be in [0, 1000], got %lld", static_cast<long long>(numAttributes));
  if (numMarkers != 0 && numMarkers != 1)
    return s.error("number of boundary markers must be 0 or 1, got %lld", static_cast<long long>(numMarkers));

  mesh->vertices.reserve(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i) {
    int64_t index = 0;
    VP_TRY(s.readInt("point index", &index));
    if (i == 0) {
      if (index != 0 && index != 1)
        return s.error("the first point index must be 0 or 1 (it sets the numbering base), got %lld",
                       static_cast<long long>(index));
      *base = index;
    } else if (index != *base + i) {
      return s.error("point indices must be consecutive: expected %lld, got %lld",
                     static_cast<long long>(*base + i), static_cast<long long>(index));
    }
    Eigen::Vector3d x;
    VP_TRY(s.readDoubleOnLine("point x coordinate", &x[0]));
    VP_TRY(s.readDoubleOnLine("point y coordinate", &x[1]));
    VP_TRY(s.readDoubleOnLine("point z coordinate", &x[2]));
    double attribute = 0.0;
    for (int64_t k = 0; k < numAttributes; ++k) VP_TRY(s.readDoubleOnLine("point attribute", &attribute));
    int64_t marker = 0;
    if (numMarkers == 1) VP_TRY(s.readIntOnLine("boundary marker", &marker));
    VP_TRY(s.expectEndOfLine("a point record (index, x, y, z, attributes, marker as the header says)"));
    mesh->vertices.push_back(x);
  }
  return expectNoMoreRecords(s, count);
}

Status readEleFile(TextScanner& s, int64_t base, TetMesh* mesh) {
  int64_t count = 0, nodesPerTet = 0, numRegionAttributes = 0;
  VP_TRY(s.readInt("number of tetrahedra", &count));
  VP_TRY(s.readIntOnLine("nodes per tetrahedron (4 or 10)", &nodesPerTet));
  VP_TRY(s.readIntOnLine("number of region attributes (0 or 1)", &numRegionAttributes));
  VP_TRY(s.expectEndOfLine("the .ele header"));
  VP_TRY(s.checkCount(count, 10, "number of tetrahedra"));
  if (nodesPerTet != 4 && nodesPerTet != 10)
    return s.error("nodes per tetrahedron must be 4 or 10, got %lld", static_cast<long long>(nodesPerTet));
  if (numRegionAttributes != 0 && numRegionAttributes != 1)
    return s.error("number of region attributes must be 0 or 1, got %lld",
                   static_cast<long long>(numRegionAttributes));

  const int64_t numPoints = static_cast<int64_t>(mesh->vertices.size());
  mesh->tets.reserve(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i) {
    int64_t index = 0;
    VP_TRY(s.readInt("tetrahedron index", &index));
    std::array<int32_t, 4> tet{};
    for (int64_t k = 0; k < nodesPerTet; ++k) {
      int64_t node = 0;
      VP_TRY(s.readIntOnLine("tetrahedron node index", &node));
      if (node < base || node >= base + numPoints)
        return s.error("node index %lld is outside the %lld points of the .node file (numbered from %lld)",
                       static_cast<long long>(node), static_cast<long long>(numPoints),
                       static_cast<long long>(base));
      // In a 10-node tet the first 4 nodes are the corners; the mid-edge nodes are
      // dropped (the validator later removes them as unused vertices).
      if (k < 4) tet[k] = static_cast<int32_t>(node - base);
    }
    double region = 0.0;
    if (numRegionAttributes == 1) VP_TRY(s.readDoubleOnLine("region attribute", &region));
    VP_TRY(s.expectEndOfLine("a tetrahedron record (index, nodes, region attribute as the header says)"));
    mesh->tets.push_back(tet);
  }
  return expectNoMoreRecords(s, count);
}

}  // namespace

Status readTetGen(const std::string& path, TetMesh* out) {
  if (out == nullptr) return fail(Status::InvalidArgument, "readTetGen: out is null");
  std::string basename = path;
  if (endsWith(path, ".node")) basename = path.substr(0, path.size() - 5);
  else if (endsWith(path, ".ele")) basename = path.substr(0, path.size() - 4);
  try {
    TetMesh mesh;
    int64_t base = 0;
    TextScanner nodes;
    VP_TRY(nodes.open(basename + ".node", '#'));
    VP_TRY(readNodeFile(nodes, &mesh, &base));
    TextScanner elements;
    VP_TRY(elements.open(basename + ".ele", '#'));
    VP_TRY(readEleFile(elements, base, &mesh));
    *out = std::move(mesh);
    return Status::Ok;
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "file '%s': out of memory", path.c_str());
  } catch (const std::exception& e) {
    return fail(Status::Internal, "file '%s': %s", path.c_str(), e.what());
  }
}

}  // namespace vp
