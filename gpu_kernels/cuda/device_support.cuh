// What the CUDA sources share: device arrays that free themselves, a CUDA error turned into
// false with its text, an event timer, and the launch geometry of one thread per item.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

namespace vp::gpu {

template <class T>
class DeviceArray {
 public:
  DeviceArray() = default;
  ~DeviceArray() { cudaFree(data_); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  cudaError_t allocate(size_t n) {
    size_ = n;
    return cudaMalloc(&data_, (n ? n : 1) * sizeof(T));
  }
  cudaError_t upload(const T* host, size_t n) {
    cudaError_t e = allocate(n);
    if (e != cudaSuccess || n == 0) return e;
    return cudaMemcpy(data_, host, n * sizeof(T), cudaMemcpyHostToDevice);
  }
  void swap(DeviceArray& other) {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
  }
  T* get() const { return data_; }
  size_t size() const { return size_; }

 private:
  T* data_ = nullptr;
  size_t size_ = 0;
};

// One thread per item, launch::kThreads to a block.
namespace launch {
constexpr int kThreads = 256;
// Blocks for `items` threads (at least one, so a launch over nothing stays valid).
inline unsigned blocks(int64_t items) {
  const int64_t b = (items + kThreads - 1) / kThreads;
  return static_cast<unsigned>(b > 0 ? b : 1);
}
// The calling thread's item.
__device__ inline int64_t index() { return blockIdx.x * int64_t(blockDim.x) + threadIdx.x; }
}  // namespace launch

inline bool failed(cudaError_t e, std::string* error) {
  if (e == cudaSuccess) e = cudaGetLastError();
  if (e == cudaSuccess) return false;
  if (error) *error = cudaGetErrorString(e);
  cudaGetLastError();  // clear a sticky-free error so later calls can report their own
  return true;
}

// Device time between start() and stopMs() on one stream (the legacy default stream unless named).
class EventTimer {
 public:
  explicit EventTimer(cudaStream_t stream = nullptr) : stream_(stream) {
    cudaEventCreate(&start_);
    cudaEventCreate(&stop_);
  }
  ~EventTimer() {
    cudaEventDestroy(start_);
    cudaEventDestroy(stop_);
  }
  void start() { cudaEventRecord(start_, stream_); }
  double stopMs() {
    cudaEventRecord(stop_, stream_);
    cudaEventSynchronize(stop_);
    float ms = 0;
    cudaEventElapsedTime(&ms, start_, stop_);
    return ms;
  }

 private:
  cudaStream_t stream_;
  cudaEvent_t start_{}, stop_{};
};

}  // namespace vp::gpu
