#include "core/regular_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

namespace vp {

Status checkRegularFile(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0)
    return fail(Status::IoError, "file '%s': cannot be opened (%s)", path.c_str(), std::strerror(errno));
  if (S_ISREG(st.st_mode)) return Status::Ok;
  const char* what = S_ISDIR(st.st_mode)    ? "a directory"
                     : S_ISFIFO(st.st_mode) ? "a FIFO"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                     : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                  : "not a regular file";
  return fail(Status::IoError, "file '%s': is %s; only regular files are read", path.c_str(), what);
}

}  // namespace vp
