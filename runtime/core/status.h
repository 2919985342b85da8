// Status codes and the thread-local last-error message shared by every runtime module.
//
// Runtime code never throws across module boundaries: a function that can fail returns
// vp::Status and, on failure, records a message naming the bad argument and its value with
// vp::fail(). The C ABI maps Status one-to-one onto vpStatus (see plugin_api).
#pragma once

#include <string>

namespace vp {

enum class Status : int {
  Ok = 0,
  InvalidArgument = 1,  // a value is out of range, NaN, malformed ...
  InvalidId = 2,        // null, stale or foreign id
  OutOfMemory = 3,
  Unsupported = 4,      // valid request the build or the current version cannot do
  IoError = 5,          // a file could not be opened or read
  ParseError = 6,       // a file was read but its content is malformed
  Busy = 7,             // another call holds the world (calls on one world must not overlap)
  Diverged = 8,         // the simulation blew up; the actor was restored
  VersionMismatch = 9,  // header and library disagree
  Internal = 10,        // a bug: an invariant of VolPhys itself was broken
  PhaseFailed = 11,     // a step completed what it could; a phase of some actor failed (its stats say which)
  NotConverged = 12,    // an iterative request (a static solve) stopped above its tolerance; nothing changed
};

// Records a printf-style message as the calling thread's last error and returns `code`.
Status fail(Status code, const char* format, ...) __attribute__((format(printf, 2, 3)));

// Prepends "context: " to the current last-error message (for callers that add a path or
// a field name to an error raised deeper down). Returns `code` unchanged.
Status addErrorContext(Status code, const std::string& context);

const char* lastError();
void clearLastError();
const char* statusName(Status code);

inline bool ok(Status s) { return s == Status::Ok; }

}  // namespace vp

// Propagates a failing status to the caller.
#define VP_TRY(expr)                                 \
  do {                                               \
    ::vp::Status vp_try_status_ = (expr);            \
    if (vp_try_status_ != ::vp::Status::Ok) return vp_try_status_; \
  } while (0)
