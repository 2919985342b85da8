#include "core/log.h"

#include <atomic>
#include <cstdarg>
#include <cstdio>

namespace vp {
namespace {

void stderrSink(LogLevel level, const char* message, void*) {
  static const char* const kNames[] = {"debug", "info", "warning", "error"};
  std::fprintf(stderr, "volphys %s: %s\n", kNames[static_cast<int>(level)], message);
}

std::atomic<LogSink> g_sink{&stderrSink};
std::atomic<void*> g_context{nullptr};
std::atomic<int> g_minLevel{static_cast<int>(LogLevel::Warning)};

}  // namespace

void setLogSink(LogSink sink, void* userContext, LogLevel minLevel) {
  g_context.store(userContext);
  g_sink.store(sink ? sink : &stderrSink);
  g_minLevel.store(static_cast<int>(sink ? minLevel : LogLevel::Warning));
}

void log(LogLevel level, const char* format, ...) {
  if (static_cast<int>(level) < g_minLevel.load() || level == LogLevel::Off) return;
  char buffer[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  g_sink.load()(level, buffer, g_context.load());
}

}  // namespace vp
