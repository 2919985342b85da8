#include "core/run_delay.h"

#if defined(__linux__)
#include <fcntl.h>
#include <unistd.h>
#endif

#include <cstdlib>

namespace vp {

#if defined(__linux__)
RunDelayReader RunDelayReader::forThisThread() {
  RunDelayReader r;
  r.fd_ = ::open("/proc/thread-self/schedstat", O_RDONLY | O_CLOEXEC);
  return r;
}

RunDelayReader& RunDelayReader::operator=(RunDelayReader&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

RunDelayReader::~RunDelayReader() {
  if (fd_ >= 0) ::close(fd_);
}

double RunDelayReader::readMs() const {
  if (fd_ < 0) return -1.0;
  // "<on-CPU ns> <run-delay ns> <timeslices>"
  char text[96];
  const ssize_t n = ::pread(fd_, text, sizeof(text) - 1, 0);
  if (n <= 0) return -1.0;
  text[n] = '\0';
  char* end = nullptr;
  std::strtoull(text, &end, 10);
  if (end == text) return -1.0;
  const char* delay = end;
  const unsigned long long ns = std::strtoull(delay, &end, 10);
  if (end == delay) return -1.0;
  return static_cast<double>(ns) * 1e-6;
}
#else
RunDelayReader RunDelayReader::forThisThread() { return RunDelayReader{}; }
RunDelayReader& RunDelayReader::operator=(RunDelayReader&& other) noexcept {
  fd_ = other.fd_;
  other.fd_ = -1;
  return *this;
}
RunDelayReader::~RunDelayReader() = default;
double RunDelayReader::readMs() const { return -1.0; }
#endif

double threadRunDelayMs() {
  thread_local const RunDelayReader self = RunDelayReader::forThisThread();
  return self.readMs();
}

}  // namespace vp
