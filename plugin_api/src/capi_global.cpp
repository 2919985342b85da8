// Library-wide calls: version, errors, hooks, build information.
#include <cmath>
#include <cstdio>
#include <thread>

#include "capi_convert.h"
#include "capi_versioned_struct.h"
#include "core/allocator.h"
#include "core/log.h"
#include "gpu_kernels/device_query.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

namespace vp::capi {

Status checkVec3(const char* field, const vpVec3& v) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    return fail(Status::InvalidArgument, "%s = (%g, %g, %g): must be finite", field, v.x, v.y, v.z);
  return Status::Ok;
}

}  // namespace vp::capi

extern "C" {

vpVersion vpGetVersion(void) { return vpVersion{VP_VERSION_MAJOR, VP_VERSION_MINOR, VP_VERSION_PATCH}; }

const char* vpGetLastError(void) { return lastError(); }

const char* vpStatusName(vpStatus status) { return statusName(static_cast<Status>(status)); }

vpStatus vpCheckHeaderVersion(uint32_t headerVersion, uint32_t worldDefSize) {
  return guarded(__func__, [&] {
    const uint32_t major = headerVersion >> 16, minor = (headerVersion >> 8) & 0xFF;
    // Before 1.0 a minor version may change struct layouts (semantic versioning's 0.x rule),
    // so only the same minor is served; from 1.0 on, older minors are.
    const bool minorServed = VP_VERSION_MAJOR == 0 ? minor == VP_VERSION_MINOR : minor <= VP_VERSION_MINOR;
    if (major != VP_VERSION_MAJOR || !minorServed)
      return fail(Status::VersionMismatch, "header version %u.%u is not served by library version %d.%d.%d", major,
                  minor, VP_VERSION_MAJOR, VP_VERSION_MINOR, VP_VERSION_PATCH);
    // Same version, so the same layout: another size means another compiler's packing.
    if (worldDefSize != sizeof(vpWorldDef))
      return fail(Status::VersionMismatch, "vpWorldDef.structSize = %u: this library's is %zu (same header version, "
                  "other packing?)", worldDefSize, sizeof(vpWorldDef));
    return Status::Ok;
  });
}

int vpWorldIdIsNull(vpWorldId id) { return id.index1 == 0; }
int vpColliderIdIsNull(vpColliderId id) { return id.index1 == 0; }

vpStatus vpSetAllocator(vpAllocFn* allocFn, vpFreeFn* freeFn, void* userContext) {
  return guarded(__func__, [&] {
    if ((allocFn == nullptr) != (freeFn == nullptr))
      return fail(Status::InvalidArgument, "vpSetAllocator: allocFn and freeFn must both be set or both be NULL");
    if (liveWorldCount() != 0)
      return fail(Status::Busy, "vpSetAllocator: %zu world(s) exist; set the allocator before creating any",
                  liveWorldCount());
    setAllocator(allocFn, freeFn, userContext);
    return Status::Ok;
  });
}

vpStatus vpSetLogCallback(vpLogFn* logFn, void* userContext, vpLogLevel minLevel) {
  return guarded(__func__, [&] {
    const int level = rawEnum(minLevel);
    if (level < vpLogLevel_Debug || level > vpLogLevel_Off)
      return fail(Status::InvalidArgument, "minLevel = %d: must be a vpLogLevel", level);
    // The runtime's sink has its own level enum; adapt instead of casting function types.
    static struct {
      vpLogFn* fn;
      void* context;
    } host;
    host.fn = logFn;
    host.context = userContext;
    auto forward = [](LogLevel messageLevel, const char* message, void*) {
      host.fn(static_cast<vpLogLevel>(messageLevel), message, host.context);
    };
    setLogSink(logFn ? +forward : nullptr, nullptr, static_cast<LogLevel>(level));
    return Status::Ok;
  });
}

vpDeviceInfo vpDefaultDeviceInfo(void) {
  vpDeviceInfo info{};
  info.structSize = sizeof info;
  return info;
}

vpStatus vpGetDeviceInfo(int32_t device, vpDeviceInfo* outInfo) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outInfo);
    const int count = gpu::cudaDeviceCount();
    gpu::DeviceProperties p;
    if (device < 0 || device >= count || !gpu::cudaDeviceProperties(device, &p))
      return fail(Status::InvalidArgument, "device = %d: must be in [0, %d) (vpBuildInfo.cudaDeviceCount)", device,
                  count);
    vpDeviceInfo info = vpDefaultDeviceInfo();
    std::snprintf(info.name, sizeof info.name, "%s", p.name.c_str());
    info.totalMemoryBytes = p.totalMemoryBytes;
    info.computeCapabilityMajor = p.computeCapabilityMajor;
    info.computeCapabilityMinor = p.computeCapabilityMinor;
    info.multiprocessorCount = p.multiprocessors;
    return writeVersioned("vpDeviceInfo", info, outInfo);
  });
}

vpStatus vpGetBuildInfo(vpBuildInfo* outInfo) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outInfo);
    outInfo->cudaCompiled = gpu::cudaCompiled() ? 1 : 0;
    outInfo->cudaDeviceCount = gpu::cudaDeviceCount();
    outInfo->hardwareThreads = static_cast<int32_t>(std::thread::hardware_concurrency());
    return Status::Ok;
  });
}

}  // extern "C"
