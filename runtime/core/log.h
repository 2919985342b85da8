// Process-wide log sink. The host may install a callback (vpSetLogCallback); by default
// warnings and errors go to stderr. Thread-safe: the sink is read under a lock-free
// snapshot so logging from task threads is allowed.
#pragma once

namespace vp {

enum class LogLevel : int { Debug = 0, Info = 1, Warning = 2, Error = 3, Off = 4 };

using LogSink = void (*)(LogLevel level, const char* message, void* userContext);

// Installs the sink (nullptr restores the stderr default). Not meant to race with logging:
// the C ABI documents that hooks are set before worlds exist.
void setLogSink(LogSink sink, void* userContext, LogLevel minLevel);

void log(LogLevel level, const char* format, ...) __attribute__((format(printf, 2, 3)));

}  // namespace vp
