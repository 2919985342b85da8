// A whitespace tokenizer over a whole text file that knows the line of every token, shared
// by the hand-written volumetric mesh importers (gmsh, tetgen, vtk).
//
// Why hand-written: assimp reads surface meshes only, and the three volumetric formats are
// simple whitespace-separated text; a small scanner gives us what a general library would
// not: error messages that name the file, the line and what was expected, and counts that
// are checked against the file size before anything is allocated (a header claiming 10^12
// nodes must produce an error, not a bad_alloc).
//
// Internal to runtime/geometry; every function returns vp::Status and never throws.
#pragma once

#include "core/status.h"

#include <cstddef>
#include <exception>
#include <new>
#include <cstdint>
#include <string>
#include <string_view>

namespace vp {

class TextScanner {
 public:
  // Reads the whole file. IoError when it cannot be opened or read.
  // `commentChar`: when non-zero, text from that character to the end of its line is
  // skipped like whitespace (tetgen's '#').
  Status open(const std::string& path, char commentChar = 0);

  // Next whitespace-separated token, crossing line ends; false at end of file.
  bool next(std::string_view* token);
  // Like next() but does not consume the token.
  bool peek(std::string_view* token);
  // True when only blanks or a comment remain on the current line.
  bool atEndOfLine();
  // Skips the rest of the current line, including its line end.
  void skipLine();
  // The rest of the current line (without the line end), consumed.
  std::string_view restOfLine();

  // Each reads one token and returns a ParseError naming `what` if it is missing or is
  // not a complete number of that kind.
  Status readInt(const char* what, int64_t* value);
  Status readDouble(const char* what, double* value);
  // Same, but the token must be on the current line (for line-structured records, so that
  // a record with a missing field is reported as such instead of eating the next line).
  Status readIntOnLine(const char* what, int64_t* value);
  Status readDoubleOnLine(const char* what, double* value);
  // The next token must be `keyword` (compared case-sensitively).
  Status expect(const char* keyword);
  // Nothing but blanks/comments may follow on the current line.
  Status expectEndOfLine(const char* after);

  // A count read from a header must be >= 0 and each item needs at least
  // `minBytesPerItem` bytes of the rest of the file; this bounds every allocation by the
  // file size.
  Status checkCount(int64_t count, size_t minBytesPerItem, const char* what);

  // ParseError "file '<path>' line <n>: <message>" where n is the line of the last token
  // read (or the current line at end of file).
  Status error(const char* format, ...) __attribute__((format(printf, 2, 3)));
  Status errorAtLine(int line, const char* format, ...) __attribute__((format(printf, 3, 4)));

  int line() const { return tokenLine_; }
  const std::string& path() const { return path_; }
  size_t bytesRemaining() const { return data_.size() - pos_; }

  // A token made printable and short enough to quote in an error message (binary
  // garbage must not end up in a log verbatim).
  static std::string quote(std::string_view token);

 private:
  void skipBlanks(bool crossLines);

  std::string path_;
  std::string data_;
  size_t pos_ = 0;
  int line_ = 1;       // line of pos_
  int tokenLine_ = 1;  // line of the last token read
  char comment_ = 0;
};

bool parseInt64(std::string_view token, int64_t* value);
bool parseDouble(std::string_view token, double* value);

// Opens `path` and runs parse(scanner) on it; an exception escaping the parser (only the
// standard library's: out of memory, or a bug) becomes a status that names the file.
template <class Parse>
Status scanFile(const std::string& path, char commentChar, Parse&& parse) {
  try {
    TextScanner scanner;
    VP_TRY(scanner.open(path, commentChar));
    return parse(scanner);
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "file '%s': out of memory", path.c_str());
  } catch (const std::exception& e) {
    return fail(Status::Internal, "file '%s': %s", path.c_str(), e.what());
  }
}

}  // namespace vp
