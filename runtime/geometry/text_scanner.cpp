#include "geometry/text_scanner.h"

#include <charconv>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <limits>
#include <new>

#include "core/regular_file.h"

namespace vp {

namespace {
// Larger text meshes than this are not realistic inputs for an interactive simulation,
// and the whole file is held in memory while parsing.
constexpr std::streamoff kMaxFileBytes = std::streamoff(2) << 30;

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

bool parseInt64(std::string_view token, int64_t* value) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  auto result = std::from_chars(token.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

bool parseDouble(std::string_view token, double* value) {
  // from_chars does not take a leading '+', which some writers emit.
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  auto result = std::from_chars(token.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

Status TextScanner::open(const std::string& path, char commentChar) {
  path_ = path;
  comment_ = commentChar;
  pos_ = 0;
  line_ = tokenLine_ = 1;
  VP_TRY(checkRegularFile(path));
  try {
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(Status::IoError, "file '%s': cannot be opened", path.c_str());
    in.seekg(0, std::ios::end);
    std::streamoff size = in.tellg();
    if (size < 0) return fail(Status::IoError, "file '%s': cannot determine its size", path.c_str());
    if (size > kMaxFileBytes)
      return fail(Status::IoError, "file '%s': %lld bytes is larger than the supported %lld",
                  path.c_str(), static_cast<long long>(size), static_cast<long long>(kMaxFileBytes));
    in.seekg(0, std::ios::beg);
    data_.resize(static_cast<size_t>(size));
    if (size > 0 && !in.read(&data_[0], size))
      return fail(Status::IoError, "file '%s': read failed", path.c_str());
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "file '%s': out of memory while reading", path.c_str());
  } catch (const std::exception& e) {
    return fail(Status::IoError, "file '%s': %s", path.c_str(), e.what());
  }
  return Status::Ok;
}

void TextScanner::skipBlanks(bool crossLines) {
  while (pos_ < data_.size()) {
    char c = data_[pos_];
    if (isBlank(c)) {
      ++pos_;
    } else if (c == '\n') {
      if (!crossLines) return;
      ++pos_;
      ++line_;
    } else if (comment_ != 0 && c == comment_) {
      while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    } else {
      return;
    }
  }
}

bool TextScanner::next(std::string_view* token) {
  skipBlanks(true);
  tokenLine_ = line_;
  if (pos_ >= data_.size()) return false;
  size_t start = pos_;
  while (pos_ < data_.size()) {
    char c = data_[pos_];
    if (isBlank(c) || c == '\n' || (comment_ != 0 && c == comment_)) break;
    ++pos_;
  }
  *token = std::string_view(data_).substr(start, pos_ - start);
  return true;
}

bool TextScanner::peek(std::string_view* token) {
  size_t pos = pos_;
  int line = line_, tokenLine = tokenLine_;
  bool found = next(token);
  pos_ = pos;
  line_ = line;
  tokenLine_ = tokenLine;
  return found;
}

bool TextScanner::atEndOfLine() {
  skipBlanks(false);
  return pos_ >= data_.size() || data_[pos_] == '\n';
}

void TextScanner::skipLine() {
  while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
  if (pos_ < data_.size()) {
    ++pos_;
    ++line_;
  }
}

std::string_view TextScanner::restOfLine() {
  tokenLine_ = line_;
  size_t start = pos_;
  while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
  std::string_view text = std::string_view(data_).substr(start, pos_ - start);
  while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
  if (pos_ < data_.size()) {
    ++pos_;
    ++line_;
  }
  return text;
}

std::string TextScanner::quote(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string out;
  for (size_t i = 0; i < token.size() && i < kMax; ++i) {
    unsigned char c = static_cast<unsigned char>(token[i]);
    out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMax) out += "...";
  return out;
}

Status TextScanner::readInt(const char* what, int64_t* value) {
  std::string_view token;
  if (!next(&token)) return error("expected %s (an integer), got end of file", what);
  if (!parseInt64(token, value))
    return error("expected %s (an integer), got '%s'", what, quote(token).c_str());
  return Status::Ok;
}

Status TextScanner::readDouble(const char* what, double* value) {
  std::string_view token;
  if (!next(&token)) return error("expected %s (a number), got end of file", what);
  if (!parseDouble(token, value))
    return error("expected %s (a number), got '%s'", what, quote(token).c_str());
  return Status::Ok;
}

Status TextScanner::readIntOnLine(const char* what, int64_t* value) {
  if (atEndOfLine()) {
    tokenLine_ = line_;
    return error("expected %s (an integer), got end of line", what);
  }
  return readInt(what, value);
}

Status TextScanner::readDoubleOnLine(const char* what, double* value) {
  if (atEndOfLine()) {
    tokenLine_ = line_;
    return error("expected %s (a number), got end of line", what);
  }
  return readDouble(what, value);
}

Status TextScanner::expect(const char* keyword) {
  std::string_view token;
  if (!next(&token)) return error("expected '%s', got end of file", keyword);
  if (token != keyword) return error("expected '%s', got '%s'", keyword, quote(token).c_str());
  return Status::Ok;
}

Status TextScanner::expectEndOfLine(const char* after) {
  if (atEndOfLine()) return Status::Ok;
  std::string_view token;
  next(&token);
  return error("expected end of line after %s, got '%s'", after, quote(token).c_str());
}

Status TextScanner::checkCount(int64_t count, size_t minBytesPerItem, const char* what) {
  if (count < 0) return error("%s must not be negative, got %lld", what, static_cast<long long>(count));
  // int32 is the index type of TetMesh; larger counts cannot be represented anyway.
  if (count > std::numeric_limits<int32_t>::max())
    return error("%s %lld is larger than the supported %d", what, static_cast<long long>(count),
                 std::numeric_limits<int32_t>::max());
  if (static_cast<uint64_t>(count) > bytesRemaining() / minBytesPerItem)
    return error("%s %lld cannot fit in the %zu bytes left in the file (truncated file or wrong count?)",
                 what, static_cast<long long>(count), bytesRemaining());
  return Status::Ok;
}

namespace {
std::string formatMessage(const char* format, va_list args) {
  char buffer[768];
  std::vsnprintf(buffer, sizeof buffer, format, args);
  return buffer;
}
}  // namespace

Status TextScanner::error(const char* format, ...) {
  va_list args;
  va_start(args, format);
  std::string message = formatMessage(format, args);
  va_end(args);
  return fail(Status::ParseError, "file '%s' line %d: %s", path_.c_str(), tokenLine_, message.c_str());
}

Status TextScanner::errorAtLine(int line, const char* format, ...) {
  va_list args;
  va_start(args, format);
  std::string message = formatMessage(format, args);
  va_end(args);
  return fail(Status::ParseError, "file '%s' line %d: %s", path_.c_str(), line, message.c_str());
}

}  // namespace vp
