// Built without CUDA: a device block system is never available (create says why), so callers
// need no build switches of their own.
#include "gpu_kernels/device_block_system.h"

namespace vp::gpu {

struct DeviceBlockSystem::Impl {};

DeviceBlockSystem::DeviceBlockSystem(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceBlockSystem::~DeviceBlockSystem() = default;

std::unique_ptr<DeviceBlockSystem> DeviceBlockSystem::create(const HostBlockSystem&, std::string* error) {
  if (error) *error = "this build has no CUDA path";
  return nullptr;
}

// Unreachable: no instance exists without CUDA.
int32_t DeviceBlockSystem::rows() const { return 0; }
bool DeviceBlockSystem::multiply(const double*, double*, bool, std::string*) { return false; }
bool DeviceBlockSystem::timeMultiply(int, bool, double*, std::string*) { return false; }
bool DeviceBlockSystem::setValues(const double*, const double*, const double*, std::string*) { return false; }
bool DeviceBlockSystem::setConstraints(const uint8_t*, const double*, std::string*) { return false; }
bool DeviceBlockSystem::solve(const double*, double*, double, int, DeviceCgForm, DeviceCgResult*, std::string*,
                              const DeviceCgControl&) {
  return false;
}
DeviceBcsr DeviceBlockSystem::bcsr() const { return DeviceBcsr{}; }

}  // namespace vp::gpu
