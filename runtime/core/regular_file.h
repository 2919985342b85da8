// Only regular files are read: a FIFO would block the reader forever, a device or a directory
// gives nothing meaningful. Every file reader checks here first.
#pragma once

#include <string>

#include "core/status.h"

namespace vp {

// Ok for a regular file (following symlinks); IoError naming the path and what it is otherwise.
Status checkRegularFile(const std::string& path);

}  // namespace vp
