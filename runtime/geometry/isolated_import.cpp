#include "geometry/isolated_import.h"

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#define VP_HAVE_FORK 1
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace vp {

#if VP_HAVE_FORK
namespace {

// The child's reply: status, message, then the mesh's vertices and triangles.
struct ReplyHeader {
  int32_t status;
  uint32_t messageBytes;
  uint64_t vertexCount;
  uint64_t triangleCount;
};

bool writeAll(int fd, const void* data, size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd, p, bytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    bytes -= static_cast<size_t>(n);
  }
  return true;
}

// The child inherits the host's mappings (libraries, thread stacks, maybe a GPU driver's
// reservations), so the cap is what it has now plus the import's allowance.
void capAddressSpace(size_t allowance) {
#if defined(__SANITIZE_THREAD__)
  (void)allowance;
#else
  long pages = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  if (pages <= 0) return;
  const rlim_t cap = static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE)) + allowance;
  struct rlimit limit = {cap, cap};
  ::setrlimit(RLIMIT_AS, &limit);
#endif
}

// A crash in the child must end it by its signal: not run the host's crash handler (a game's
// crash reporter) or a sanitizer's, which would report it as the host's and exit normally.
void restoreDefaultCrashSignals() {
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP}) ::signal(sig, SIG_DFL);
}

[[noreturn]] void runChild(int fd, const std::string& path, SurfaceImporter importer, const ImportLimits& limits) {
  restoreDefaultCrashSignals();
  capAddressSpace(limits.memoryBytes);
  SurfaceMesh mesh;
  Status s;
  try {
    s = importer(path, &mesh);
  } catch (...) {
    s = fail(Status::ParseError, "file '%s': the importer threw", path.c_str());
  }
  const std::string message = ok(s) ? std::string() : std::string(lastError());
  ReplyHeader h{static_cast<int32_t>(s), static_cast<uint32_t>(message.size()), mesh.vertices.size(),
                mesh.triangles.size()};
  const bool sent = writeAll(fd, &h, sizeof h) && writeAll(fd, message.data(), message.size()) &&
                    writeAll(fd, mesh.vertices.data(), mesh.vertices.size() * sizeof(mesh.vertices[0])) &&
                    writeAll(fd, mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
  ::_exit(sent ? 0 : 1);  // no atexit handlers, no flushing of the host's buffers
}

// Reads until EOF or the deadline; false on timeout.
bool readUntilEof(int fd, std::chrono::steady_clock::time_point deadline, std::vector<char>* bytes) {
  char buffer[1 << 16];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    struct pollfd p = {fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return ready < 0;  // an error: the reply check below reports it
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    bytes->insert(bytes->end(), buffer, buffer + n);
  }
}

// The child's exit: -1 if it was already reaped by the host, else the waitpid status.
int reap(pid_t pid) {
  int status = 0;
  for (;;) {
    if (::waitpid(pid, &status, 0) == pid) return status;
    if (errno != EINTR) return -1;
  }
}

Status decodeReply(const std::string& path, const std::vector<char>& bytes, SurfaceMesh* out) {
  ReplyHeader h;
  if (bytes.size() < sizeof h)
    return fail(Status::ParseError, "file '%s': the importer ended without a reply", path.c_str());
  std::memcpy(&h, bytes.data(), sizeof h);
  const size_t vertexBytes = sizeof(decltype(SurfaceMesh::vertices)::value_type);
  const size_t triangleBytes = sizeof(decltype(SurfaceMesh::triangles)::value_type);
  const uint64_t limit = bytes.size();
  if (h.messageBytes > limit || h.vertexCount > limit / vertexBytes || h.triangleCount > limit / triangleBytes ||
      sizeof h + h.messageBytes + h.vertexCount * vertexBytes + h.triangleCount * triangleBytes != bytes.size())
    return fail(Status::ParseError, "file '%s': the importer's reply was cut short", path.c_str());
  const char* p = bytes.data() + sizeof h;
  if (h.status != static_cast<int32_t>(Status::Ok)) {
    const bool known = h.status > 0 && h.status <= static_cast<int32_t>(Status::Internal);
    return fail(known ? static_cast<Status>(h.status) : Status::Internal, "%.*s", static_cast<int>(h.messageBytes), p);
  }
  p += h.messageBytes;
  SurfaceMesh mesh;
  mesh.vertices.resize(h.vertexCount);
  mesh.triangles.resize(h.triangleCount);
  static_assert(sizeof(decltype(SurfaceMesh::vertices)::value_type) == 3 * sizeof(double), "vertices are 3 doubles");
  std::memcpy(static_cast<void*>(mesh.vertices.data()), p, h.vertexCount * vertexBytes);
  std::memcpy(mesh.triangles.data(), p + h.vertexCount * vertexBytes, h.triangleCount * triangleBytes);
  *out = std::move(mesh);
  return Status::Ok;
}

}  // namespace

Status importIsolated(const std::string& path, SurfaceImporter importer, const ImportLimits& limits,
                      SurfaceMesh* out) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    return fail(Status::OutOfMemory, "file '%s': no pipe for the importer (%s)", path.c_str(), std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return fail(Status::OutOfMemory, "file '%s': cannot start the importer process (%s)", path.c_str(),
                std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    runChild(fds[1], path, importer, limits);
  }
  ::close(fds[1]);
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(limits.wallSeconds));
  std::vector<char> bytes;
  bool finished = false;
  try {
    finished = readUntilEof(fds[0], deadline, &bytes);
  } catch (const std::bad_alloc&) {
    ::kill(pid, SIGKILL);
    ::close(fds[0]);
    reap(pid);
    return fail(Status::OutOfMemory, "file '%s': out of memory receiving the mesh", path.c_str());
  }
  ::close(fds[0]);
  if (!finished) {
    ::kill(pid, SIGKILL);
    reap(pid);
    return fail(Status::ParseError, "file '%s': the importer did not finish within %g s and was stopped",
                path.c_str(), limits.wallSeconds);
  }
  const int status = reap(pid);
  if (status != -1 && WIFSIGNALED(status))
    return fail(Status::ParseError, "file '%s': the importer crashed on it (signal %d, %s): the file is malformed",
                path.c_str(), WTERMSIG(status), ::strsignal(WTERMSIG(status)));
  return decodeReply(path, bytes, out);
}

#else

Status importIsolated(const std::string& path, SurfaceImporter importer, const ImportLimits&, SurfaceMesh* out) {
  return importer(path, out);
}

#endif

}  // namespace vp
