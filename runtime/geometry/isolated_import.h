// Runs a surface-file importer (assimp) where its failures cannot reach the host. assimp
// crashes (null dereferences, failed internal asserts that abort), loops or exhausts memory on
// malformed files; one bad asset must not kill the host that loads it. On POSIX the importer
// runs in a short-lived child process (fork) that sends the triangles back over a pipe, under
// a wall-time limit and an address-space cap: a crash, a hang or running out of memory there
// becomes a ParseError (or OutOfMemory) here, naming the file and what happened.
//
// Limits of the isolation: the memory cap is not set under ThreadSanitizer (it maps its shadow
// as it goes; AddressSanitizer reserves its shadow up front, which the cap, relative to what the
// child inherits, leaves out); where fork is unavailable (Windows) the importer runs
// in-process. A host that reaps every child itself (SIGCHLD ignored) gets the result all the
// same: the reply on the pipe is complete or the import failed. The child of a multithreaded
// host runs only the importer, but a lock another host thread held at the fork (beyond glibc's
// malloc, which fork handles) could stall it: the time limit then ends it.
#pragma once

#include <cstddef>
#include <string>

#include "core/status.h"
#include "geometry/surface_mesh.h"

namespace vp {

struct ImportLimits {
  // A large legitimate asset (a 100 MB FBX) imports in seconds; a malformed header that
  // promises 10^8 elements runs for minutes.
  double wallSeconds = 20.0;
  // Address space the child may add to what it inherits from the host.
  std::size_t memoryBytes = std::size_t(4) << 30;
};

using SurfaceImporter = Status (*)(const std::string& path, SurfaceMesh* out);

// Imports path with importer in a child process within limits. `*out` is unchanged on error.
Status importIsolated(const std::string& path, SurfaceImporter importer, const ImportLimits& limits,
                      SurfaceMesh* out);

}  // namespace vp
