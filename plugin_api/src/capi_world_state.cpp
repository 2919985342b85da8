// Saved world states: vpWorldSaveState, vpWorldRestoreState (runtime/world_state.cpp does
// the work).
#include <cstring>

#include "capi_convert.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

extern "C" {

vpStatus vpWorldSaveState(vpWorldId id, void* buffer, size_t capacity, size_t* outSize) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outSize);
    if (buffer == nullptr && capacity != 0)
      return fail(Status::InvalidArgument, "buffer is NULL with capacity = %zu (capacity 0 asks for the size)",
                  capacity);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    std::vector<uint8_t> state;
    VP_TRY(w->saveState(&state));
    *outSize = state.size();
    if (buffer == nullptr) return Status::Ok;
    if (capacity < state.size())
      return fail(Status::InvalidArgument, "capacity = %zu: the state needs %zu bytes (*outSize)", capacity,
                  state.size());
    std::memcpy(buffer, state.data(), state.size());
    return Status::Ok;
  });
}

vpStatus vpWorldRestoreState(vpWorldId id, const void* buffer, size_t size) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(buffer);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    return w->restoreState(static_cast<const uint8_t*>(buffer), size);
  });
}

}  // extern "C"
