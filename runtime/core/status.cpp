#include "core/status.h"

#include <cstdarg>
#include <cstdio>

namespace vp {
namespace {
thread_local std::string t_lastError;
}

Status fail(Status code, const char* format, ...) {
  char buffer[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  t_lastError = buffer;
  return code;
}

Status addErrorContext(Status code, const std::string& context) {
  t_lastError = context + ": " + t_lastError;
  return code;
}

const char* lastError() { return t_lastError.c_str(); }
void clearLastError() { t_lastError.clear(); }

const char* statusName(Status code) {
  switch (code) {
    case Status::Ok: return "Ok";
    case Status::InvalidArgument: return "InvalidArgument";
    case Status::InvalidId: return "InvalidId";
    case Status::OutOfMemory: return "OutOfMemory";
    case Status::Unsupported: return "Unsupported";
    case Status::IoError: return "IoError";
    case Status::ParseError: return "ParseError";
    case Status::Busy: return "Busy";
    case Status::Diverged: return "Diverged";
    case Status::VersionMismatch: return "VersionMismatch";
    case Status::Internal: return "Internal";
    case Status::PhaseFailed: return "PhaseFailed";
    case Status::NotConverged: return "NotConverged";
  }
  return "Unknown";
}

}  // namespace vp
