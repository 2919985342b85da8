// Hand-written because assimp reads surface meshes only (see text_scanner.h), and linking
// all of VTK for one legacy text format would be out of proportion.
// Format reference: "VTK File Formats", section "Simple Legacy Formats"
// (https://docs.vtk.org/en/latest/design_documents/VTKFileFormats.html).
#include "geometry/vtk_reader.h"

#include "geometry/text_scanner.h"

#include <algorithm>
#include <cctype>
#include <new>
#include <string>
#include <string_view>
#include <vector>

namespace vp {
namespace {

constexpr int64_t kVtkTetra = 10;

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

bool isNumericType(const std::string& type) {
  static const char* kTypes[] = {"FLOAT", "DOUBLE"};
  return std::find_if(std::begin(kTypes), std::end(kTypes), [&](const char* t) { return type == t; }) !=
         std::end(kTypes);
}

bool isIntegerType(const std::string& type) {
  static const char* kTypes[] = {"INT", "UNSIGNED_INT", "LONG", "UNSIGNED_LONG", "VTKTYPEINT64",
                                 "VTKTYPEINT32", "SHORT", "UNSIGNED_SHORT"};
  return std::find_if(std::begin(kTypes), std::end(kTypes), [&](const char* t) { return type == t; }) !=
         std::end(kTypes);
}

struct VtkContent {
  Array<Eigen::Vector3d> points;
  // Cell i uses connectivity[offsets[i] .. offsets[i+1]).
  Array<int64_t> offsets;
  Array<int64_t> connectivity;
  std::vector<int> cellLines;  // where each cell's list starts (classic layout) for errors
  int cellsLine = 0;
  Array<int64_t> types;
  int typesLine = 0;
  bool sawPoints = false, sawCells = false, sawTypes = false;
};

Status readPoints(TextScanner& s, VtkContent& c) {
  int64_t count = 0;
  VP_TRY(s.readInt("number of points", &count));
  std::string_view typeToken;
  if (!s.next(&typeToken)) return s.error("expected the POINTS data type (float or double), got end of file");
  std::string type = upper(typeToken);
  if (!isNumericType(type))
    return s.error("expected the POINTS data type float or double, got '%s'", TextScanner::quote(typeToken).c_str());
  VP_TRY(s.checkCount(count, 6, "number of points"));
  c.points.resize(static_cast<size_t>(count));
  for (auto& p : c.points)
    for (int k = 0; k < 3; ++k) VP_TRY(s.readDouble("point coordinate", &p[k]));
  c.sawPoints = true;
  return Status::Ok;
}

Status readIntArray(TextScanner& s, const char* keyword, int64_t count, Array<int64_t>* values) {
  VP_TRY(s.expect(keyword));
  std::string_view typeToken;
  if (!s.next(&typeToken)) return s.error("expected the %s data type, got end of file", keyword);
  if (!isIntegerType(upper(typeToken)))
    return s.error("expected an integer data type for %s, got '%s'", keyword, TextScanner::quote(typeToken).c_str());
  values->resize(static_cast<size_t>(count));
  for (auto& v : *values) VP_TRY(s.readInt(keyword, &v));
  return Status::Ok;
}

Status readCells(TextScanner& s, VtkContent& c) {
  int64_t first = 0, second = 0;
  VP_TRY(s.readInt("number of cells", &first));
  VP_TRY(s.readInt("size of the cell list", &second));
  c.cellsLine = s.line();
  std::string_view token;
  if (s.peek(&token) && upper(token) == "OFFSETS") {
    // Version 5.1: "CELLS <numOffsets = numCells + 1> <connectivity size>".
    VP_TRY(s.checkCount(first, 2, "number of offsets"));
    VP_TRY(s.checkCount(second, 2, "connectivity size"));
    if (first < 1) return s.error("number of offsets must be at least 1, got %lld", static_cast<long long>(first));
    VP_TRY(readIntArray(s, "OFFSETS", first, &c.offsets));
    VP_TRY(readIntArray(s, "CONNECTIVITY", second, &c.connectivity));
    if (c.offsets[0] != 0) return s.errorAtLine(c.cellsLine, "OFFSETS must start with 0, got %lld",
                                                static_cast<long long>(c.offsets[0]));
    for (size_t i = 1; i < c.offsets.size(); ++i)
      if (c.offsets[i] < c.offsets[i - 1] || c.offsets[i] > second)
        return s.errorAtLine(c.cellsLine, "OFFSETS[%zu] = %lld is not between the previous offset and the "
                             "connectivity size %lld", i, static_cast<long long>(c.offsets[i]),
                             static_cast<long long>(second));
    c.cellLines.assign(c.offsets.size() - 1, c.cellsLine);
  } else {
    // Classic: "CELLS <numCells> <size>" then per cell "<n> <id> ... <id>"; size counts all.
    VP_TRY(s.checkCount(first, 2, "number of cells"));
    VP_TRY(s.checkCount(second, 2, "size of the cell list"));
    c.offsets.reserve(static_cast<size_t>(first) + 1);
    c.connectivity.reserve(static_cast<size_t>(second));
    c.offsets.push_back(0);
    int64_t used = 0;
    for (int64_t i = 0; i < first; ++i) {
      int64_t n = 0;
      VP_TRY(s.readInt("number of points of the cell", &n));
      c.cellLines.push_back(s.line());
      if (n < 0 || n > second - used - 1)
        return s.error("cell %lld has %lld points, which overruns the CELLS size %lld",
                       static_cast<long long>(i), static_cast<long long>(n), static_cast<long long>(second));
      for (int64_t k = 0; k < n; ++k) {
        int64_t id = 0;
        VP_TRY(s.readInt("cell point index", &id));
        c.connectivity.push_back(id);
      }
      used += 1 + n;
      c.offsets.push_back(static_cast<int64_t>(c.connectivity.size()));
    }
    if (used != second)
      return s.error("the %lld cells use %lld values but the CELLS size says %lld", static_cast<long long>(first),
                     static_cast<long long>(used), static_cast<long long>(second));
  }
  c.sawCells = true;
  return Status::Ok;
}

Status readCellTypes(TextScanner& s, VtkContent& c) {
  int64_t count = 0;
  VP_TRY(s.readInt("number of cell types", &count));
  c.typesLine = s.line();
  VP_TRY(s.checkCount(count, 2, "number of cell types"));
  c.types.resize(static_cast<size_t>(count));
  for (auto& t : c.types) VP_TRY(s.readInt("cell type", &t));
  c.sawTypes = true;
  return Status::Ok;
}

// VTK 9 writes "METADATA" blocks (key/value lines ended by a blank line) after arrays.
void skipMetadata(TextScanner& s) {
  s.skipLine();
  while (s.bytesRemaining() > 0) {
    std::string_view line = s.restOfLine();
    if (line.empty()) return;
  }
}

// "FIELD <name> <numArrays>" followed per array by "<name> <components> <tuples> <type>"
// and components * tuples values (VTK writes e.g. a TIME array here).
Status skipFieldData(TextScanner& s) {
  std::string_view name;
  if (!s.next(&name)) return s.error("expected the FIELD name, got end of file");
  int64_t numArrays = 0;
  VP_TRY(s.readInt("number of FIELD arrays", &numArrays));
  VP_TRY(s.checkCount(numArrays, 8, "number of FIELD arrays"));
  for (int64_t a = 0; a < numArrays; ++a) {
    std::string_view arrayName, type;
    if (!s.next(&arrayName)) return s.error("expected a FIELD array name, got end of file");
    int64_t components = 0, tuples = 0;
    VP_TRY(s.readInt("number of components", &components));
    VP_TRY(s.readInt("number of tuples", &tuples));
    if (!s.next(&type)) return s.error("expected the FIELD array data type, got end of file");
    if (components < 0 || tuples < 0 || (components > 0 && tuples > INT64_MAX / components))
      return s.error("FIELD array size %lld x %lld is invalid", static_cast<long long>(components),
                     static_cast<long long>(tuples));
    VP_TRY(s.checkCount(components * tuples, 2, "number of FIELD values"));
    double ignored = 0.0;
    for (int64_t k = 0; k < components * tuples; ++k) VP_TRY(s.readDouble("FIELD value", &ignored));
    std::string_view next;
    if (s.peek(&next) && upper(next) == "METADATA") skipMetadata(s);
  }
  return Status::Ok;
}

Status parse(TextScanner& s, TetMesh* out) {
  std::string_view header = s.restOfLine();
  if (header.substr(0, 5) != "# vtk" && header.substr(0, 5) != "# VTK")
    return s.error("expected the legacy VTK header '# vtk DataFile Version x.y', got '%s'",
                   TextScanner::quote(header).c_str());
  s.restOfLine();  // title
  std::string_view encoding;
  if (!s.next(&encoding)) return s.error("expected ASCII or BINARY, got end of file");
  std::string enc = upper(encoding);
  if (enc == "BINARY")
    return fail(Status::Unsupported, "file '%s': legacy binary VTK is not supported; write it as ASCII",
                s.path().c_str());
  if (enc != "ASCII") return s.error("expected ASCII or BINARY, got '%s'", TextScanner::quote(encoding).c_str());
  VP_TRY(s.expect("DATASET"));
  std::string_view dataset;
  if (!s.next(&dataset)) return s.error("expected the DATASET kind, got end of file");
  if (upper(dataset) != "UNSTRUCTURED_GRID")
    return fail(Status::Unsupported, "file '%s' line %d: DATASET %s is not supported (only UNSTRUCTURED_GRID)",
                s.path().c_str(), s.line(), TextScanner::quote(dataset).c_str());

  VtkContent c;
  std::string_view token;
  while (s.next(&token)) {
    std::string keyword = upper(token);
    if (keyword == "POINTS") {
      if (c.sawPoints) return s.error("second POINTS section");
      VP_TRY(readPoints(s, c));
    } else if (keyword == "CELLS") {
      if (c.sawCells) return s.error("second CELLS section");
      VP_TRY(readCells(s, c));
    } else if (keyword == "CELL_TYPES") {
      if (c.sawTypes) return s.error("second CELL_TYPES section");
      VP_TRY(readCellTypes(s, c));
    } else if (keyword == "METADATA") {
      skipMetadata(s);
    } else if (keyword == "FIELD") {
      VP_TRY(skipFieldData(s));
    } else if (keyword == "POINT_DATA" || keyword == "CELL_DATA") {
      break;  // attributes are not needed for the geometry
    } else {
      return s.error("expected POINTS, CELLS, CELL_TYPES, POINT_DATA or CELL_DATA, got '%s'",
                     TextScanner::quote(token).c_str());
    }
  }
  if (!c.sawPoints) return s.error("the file has no POINTS section");
  if (!c.sawCells) return s.error("the file has no CELLS section");
  if (!c.sawTypes) return s.error("the file has no CELL_TYPES section");
  const size_t numCells = c.offsets.size() - 1;
  if (c.types.size() != numCells)
    return s.errorAtLine(c.typesLine, "CELL_TYPES lists %zu types but CELLS has %zu cells", c.types.size(),
                         numCells);

  TetMesh mesh;
  const int64_t numPoints = static_cast<int64_t>(c.points.size());
  for (size_t i = 0; i < numCells; ++i) {
    if (c.types[i] != kVtkTetra) continue;
    const int64_t begin = c.offsets[i], size = c.offsets[i + 1] - begin;
    if (size != 4)
      return s.errorAtLine(c.cellLines[i], "cell %zu has type 10 (tetra) but %lld points instead of 4", i,
                           static_cast<long long>(size));
    std::array<int32_t, 4> tet{};
    for (int k = 0; k < 4; ++k) {
      const int64_t id = c.connectivity[static_cast<size_t>(begin + k)];
      if (id < 0 || id >= numPoints)
        return s.errorAtLine(c.cellLines[i], "cell %zu uses point %lld, outside the %lld POINTS", i,
                             static_cast<long long>(id), static_cast<long long>(numPoints));
      tet[k] = static_cast<int32_t>(id);
    }
    mesh.tets.push_back(tet);
  }
  if (mesh.tets.empty())
    return s.errorAtLine(c.typesLine, "no tetrahedra (cell type 10) among the %zu cells", numCells);
  mesh.vertices = std::move(c.points);
  *out = std::move(mesh);
  return Status::Ok;
}

}  // namespace

Status readVtk(const std::string& path, TetMesh* out) {
  if (out == nullptr) return fail(Status::InvalidArgument, "readVtk: out is null");
  return scanFile(path, 0, [&](TextScanner& scanner) { return parse(scanner, out); });
}

}  // namespace vp
