// Hand-written because assimp reads surface meshes only (see text_scanner.h).
// Format reference: https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format (4.1) and
// the "Legacy formats" section of the same manual (2.2).
#include "geometry/gmsh_reader.h"

#include "geometry/text_scanner.h"

#include <cmath>
#include <new>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace vp {
namespace {

constexpr int64_t kTet4 = 4;

// Elements are resolved from node tags to vertex indices after the whole file is read, so
// that a tet naming an undefined node can be reported at its own line.
struct PendingTet {
  std::array<int64_t, 4> nodeTags;
  int line;
};

struct GmshContent {
  Array<Eigen::Vector3d> vertices;
  std::unordered_map<int64_t, int32_t> indexOfTag;
  std::vector<PendingTet> tets;
  bool sawNodes = false;
  bool sawElements = false;
  int64_t skippedElements = 0;
  int64_t skippedTet10 = 0;
};

Status addNode(TextScanner& s, GmshContent& c, int64_t tag, const Eigen::Vector3d& x) {
  if (tag <= 0) return s.error("node tag must be positive, got %lld", static_cast<long long>(tag));
  auto inserted = c.indexOfTag.emplace(tag, static_cast<int32_t>(c.vertices.size()));
  if (!inserted.second) return s.error("node tag %lld is defined twice", static_cast<long long>(tag));
  c.vertices.push_back(x);
  return Status::Ok;
}

Status readPoint(TextScanner& s, Eigen::Vector3d* x) {
  VP_TRY(s.readDouble("node x coordinate", &(*x)[0]));
  VP_TRY(s.readDouble("node y coordinate", &(*x)[1]));
  VP_TRY(s.readDouble("node z coordinate", &(*x)[2]));
  return Status::Ok;
}

// Reads the 4 node tags of a tet and requires the line to end there.
Status readTetNodes(TextScanner& s, GmshContent& c) {
  PendingTet tet{};
  for (int k = 0; k < 4; ++k) VP_TRY(s.readIntOnLine("tetrahedron node tag", &tet.nodeTags[k]));
  tet.line = s.line();
  VP_TRY(s.expectEndOfLine("the 4 node tags of a tetrahedron (element type 4)"));
  c.tets.push_back(tet);
  return Status::Ok;
}

// The tag of an element, or a clear error when a section ends before its declared count.
Status readElementTag(TextScanner& s, int64_t index, int64_t count, int64_t* tag) {
  std::string_view token;
  if (s.peek(&token) && !token.empty() && token[0] == '$') {
    s.next(&token);
    return s.error("expected element %lld of %lld, got '%s' (element count too large?)",
                   static_cast<long long>(index + 1), static_cast<long long>(count),
                   TextScanner::quote(token).c_str());
  }
  return s.readInt("element tag", tag);
}

Status readNodesV2(TextScanner& s, GmshContent& c) {
  int64_t count = 0;
  VP_TRY(s.readInt("number of nodes", &count));
  VP_TRY(s.checkCount(count, 8, "number of nodes"));
  c.vertices.reserve(static_cast<size_t>(count));
  c.indexOfTag.reserve(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i) {
    int64_t tag = 0;
    Eigen::Vector3d x;
    VP_TRY(s.readInt("node tag", &tag));
    VP_TRY(readPoint(s, &x));
    VP_TRY(addNode(s, c, tag, x));
  }
  return s.expect("$EndNodes");
}

Status readElementsV2(TextScanner& s, GmshContent& c) {
  int64_t count = 0;
  VP_TRY(s.readInt("number of elements", &count));
  VP_TRY(s.checkCount(count, 8, "number of elements"));
  for (int64_t i = 0; i < count; ++i) {
    int64_t tag = 0, type = 0, numTags = 0, ignored = 0;
    VP_TRY(readElementTag(s, i, count, &tag));
    VP_TRY(s.readIntOnLine("element type", &type));
    VP_TRY(s.readIntOnLine("number of element tags", &numTags));
    if (numTags < 0 || numTags > 1000)
      return s.error("number of element tags must be in [0, 1000], got %lld", static_cast<long long>(numTags));
    for (int64_t k = 0; k < numTags; ++k) VP_TRY(s.readIntOnLine("element tag value", &ignored));
    if (type == kTet4) {
      VP_TRY(readTetNodes(s, c));
    } else {
      // Elements are one per line; the node count of every other type need not be known.
      if (type == 11) ++c.skippedTet10;
      ++c.skippedElements;
      s.skipLine();
    }
  }
  return s.expect("$EndElements");
}

Status readNodesV4(TextScanner& s, GmshContent& c) {
  int64_t numBlocks = 0, numNodes = 0, minTag = 0, maxTag = 0;
  VP_TRY(s.readInt("number of node entity blocks", &numBlocks));
  VP_TRY(s.readInt("number of nodes", &numNodes));
  VP_TRY(s.readInt("minimum node tag", &minTag));
  VP_TRY(s.readInt("maximum node tag", &maxTag));
  VP_TRY(s.checkCount(numBlocks, 8, "number of node entity blocks"));
  VP_TRY(s.checkCount(numNodes, 8, "number of nodes"));
  c.vertices.reserve(static_cast<size_t>(numNodes));
  c.indexOfTag.reserve(static_cast<size_t>(numNodes));
  Array<int64_t> tags;
  for (int64_t b = 0; b < numBlocks; ++b) {
    int64_t entityDim = 0, entityTag = 0, parametric = 0, inBlock = 0;
    VP_TRY(s.readInt("node block entity dimension", &entityDim));
    if (entityDim < 0 || entityDim > 3)
      return s.error("node block entity dimension must be 0..3, got %lld", static_cast<long long>(entityDim));
    VP_TRY(s.readInt("node block entity tag", &entityTag));
    VP_TRY(s.readInt("node block parametric flag", &parametric));
    if (parametric != 0 && parametric != 1)
      return s.error("node block parametric flag must be 0 or 1, got %lld", static_cast<long long>(parametric));
    VP_TRY(s.readInt("number of nodes in block", &inBlock));
    VP_TRY(s.checkCount(inBlock, 8, "number of nodes in block"));
    if (static_cast<int64_t>(c.vertices.size()) + inBlock > numNodes)
      return s.error("node blocks hold more than the %lld nodes declared in the $Nodes header",
                     static_cast<long long>(numNodes));
    // 4.1 lists a block's tags first, then its coordinates.
    tags.resize(static_cast<size_t>(inBlock));
    for (int64_t i = 0; i < inBlock; ++i) VP_TRY(s.readInt("node tag", &tags[i]));
    for (int64_t i = 0; i < inBlock; ++i) {
      Eigen::Vector3d x;
      VP_TRY(readPoint(s, &x));
      double ignored = 0.0;
      if (parametric)
        for (int64_t k = 0; k < entityDim; ++k) VP_TRY(s.readDouble("parametric coordinate", &ignored));
      VP_TRY(addNode(s, c, tags[i], x));
    }
  }
  if (static_cast<int64_t>(c.vertices.size()) != numNodes)
    return s.error("node blocks hold %zu nodes but the $Nodes header declared %lld", c.vertices.size(),
                   static_cast<long long>(numNodes));
  return s.expect("$EndNodes");
}

Status readElementsV4(TextScanner& s, GmshContent& c) {
  int64_t numBlocks = 0, numElements = 0, minTag = 0, maxTag = 0;
  VP_TRY(s.readInt("number of element entity blocks", &numBlocks));
  VP_TRY(s.readInt("number of elements", &numElements));
  VP_TRY(s.readInt("minimum element tag", &minTag));
  VP_TRY(s.readInt("maximum element tag", &maxTag));
  VP_TRY(s.checkCount(numBlocks, 8, "number of element entity blocks"));
  VP_TRY(s.checkCount(numElements, 4, "number of elements"));
  int64_t seen = 0;
  for (int64_t b = 0; b < numBlocks; ++b) {
    int64_t entityDim = 0, entityTag = 0, type = 0, inBlock = 0;
    VP_TRY(s.readInt("element block entity dimension", &entityDim));
    VP_TRY(s.readInt("element block entity tag", &entityTag));
    VP_TRY(s.readInt("element type", &type));
    VP_TRY(s.readInt("number of elements in block", &inBlock));
    VP_TRY(s.checkCount(inBlock, 4, "number of elements in block"));
    if (seen + inBlock > numElements)
      return s.error("element blocks hold more than the %lld elements declared in the $Elements header",
                     static_cast<long long>(numElements));
    for (int64_t i = 0; i < inBlock; ++i) {
      int64_t tag = 0;
      VP_TRY(readElementTag(s, seen + i, numElements, &tag));
      if (type == kTet4) {
        VP_TRY(readTetNodes(s, c));
      } else {
        if (type == 11) ++c.skippedTet10;
        ++c.skippedElements;
        s.skipLine();
      }
    }
    seen += inBlock;
  }
  if (seen != numElements)
    return s.error("element blocks hold %lld elements but the $Elements header declared %lld",
                   static_cast<long long>(seen), static_cast<long long>(numElements));
  return s.expect("$EndElements");
}

// Skips a section this reader does not need ($PhysicalNames, $Entities, $NodeData ...).
Status skipSection(TextScanner& s, std::string_view name) {
  int startLine = s.line();
  std::string end = "$End" + std::string(name.substr(1));
  std::string_view token;
  while (s.next(&token)) {
    if (token == end) return Status::Ok;
  }
  return s.errorAtLine(startLine, "section '%s' has no '%s'", TextScanner::quote(name).c_str(), end.c_str());
}

Status parse(TextScanner& s, TetMesh* out) {
  VP_TRY(s.expect("$MeshFormat"));
  std::string_view versionToken;
  double version = 0.0;
  if (!s.next(&versionToken) || !parseDouble(versionToken, &version))
    return s.error("expected the format version (a number such as 2.2 or 4.1), got '%s'",
                   TextScanner::quote(versionToken).c_str());
  int64_t fileType = 0, dataSize = 0;
  VP_TRY(s.readInt("file type (0 = ASCII, 1 = binary)", &fileType));
  VP_TRY(s.readInt("data size", &dataSize));
  if (fileType == 1)
    return fail(Status::Unsupported,
                "file '%s': binary .msh is not supported; export it as ASCII (gmsh: -format msh41 "
                "without -bin, or Mesh.Binary = 0)",
                s.path().c_str());
  if (fileType != 0)
    return s.error("file type must be 0 (ASCII) or 1 (binary), got %lld", static_cast<long long>(fileType));
  const bool v2 = version >= 2.0 && version < 3.0;
  const bool v41 = std::fabs(version - 4.1) < 1e-9;
  if (!v2 && !v41)
    return fail(Status::Unsupported, "file '%s': .msh version %s is not supported (2.2 and 4.1 are)",
                s.path().c_str(), TextScanner::quote(versionToken).c_str());
  VP_TRY(s.expect("$EndMeshFormat"));

  GmshContent c;
  std::string_view token;
  while (s.next(&token)) {
    if (token == "$Nodes") {
      if (c.sawNodes) return s.error("second $Nodes section (only one is supported)");
      c.sawNodes = true;
      VP_TRY(v2 ? readNodesV2(s, c) : readNodesV4(s, c));
    } else if (token == "$Elements") {
      if (c.sawElements) return s.error("second $Elements section (only one is supported)");
      c.sawElements = true;
      VP_TRY(v2 ? readElementsV2(s, c) : readElementsV4(s, c));
    } else if (token.size() > 1 && token[0] == '$' && token.substr(0, 4) != "$End") {
      VP_TRY(skipSection(s, token));
    } else {
      return s.error("expected a section such as '$Nodes' or '$Elements', got '%s'",
                     TextScanner::quote(token).c_str());
    }
  }
  if (!c.sawNodes) return s.error("the file has no $Nodes section");
  if (!c.sawElements) return s.error("the file has no $Elements section");
  if (c.tets.empty()) {
    if (c.skippedTet10 > 0)
      return s.error("no 4-node tetrahedra (element type 4); the file has %lld 10-node tetrahedra "
                     "(type 11), export a linear mesh (Mesh.ElementOrder = 1)",
                     static_cast<long long>(c.skippedTet10));
    return s.error("no 4-node tetrahedra (element type 4) among the %lld elements",
                   static_cast<long long>(c.skippedElements));
  }

  TetMesh mesh;
  mesh.tets.reserve(c.tets.size());
  for (const PendingTet& pending : c.tets) {
    std::array<int32_t, 4> tet{};
    for (int k = 0; k < 4; ++k) {
      auto found = c.indexOfTag.find(pending.nodeTags[k]);
      if (found == c.indexOfTag.end())
        return s.errorAtLine(pending.line, "tetrahedron uses node tag %lld, which $Nodes does not define",
                             static_cast<long long>(pending.nodeTags[k]));
      tet[k] = found->second;
    }
    mesh.tets.push_back(tet);
  }
  mesh.vertices = std::move(c.vertices);
  *out = std::move(mesh);
  return Status::Ok;
}

}  // namespace

Status readGmsh(const std::string& path, TetMesh* out) {
  if (out == nullptr) return fail(Status::InvalidArgument, "readGmsh: out is null");
  return scanFile(path, 0, [&](TextScanner& scanner) { return parse(scanner, out); });
}

}  // namespace vp
