#include "capi_versioned_struct.h"

#include <algorithm>

namespace vp::capi {

Status checkVersionedSize(const char* structName, uint32_t given, size_t size, const size_t* fieldOffsets,
                          size_t count) {
  if (given == size || std::find(fieldOffsets, fieldOffsets + count, given) != fieldOffsets + count)
    return Status::Ok;
  if (given > size)
    return fail(Status::VersionMismatch,
                "%s.structSize = %u: larger than this library's %zu (the header is newer than the library)",
                structName, given, size);
  return fail(Status::VersionMismatch,
              "%s.structSize = %u: neither this library's %zu nor where one of its fields begins (an older "
              "header's size); start from vpDefault%s()",
              structName, given, size, structName + 2);
}

}  // namespace vp::capi
