// Host-replaceable allocation for VolPhys' bulk arrays (simulation state, matrices, grids)
// and for Bullet. Small bookkeeping objects (strings, maps of names) use the C++ heap:
// replacing operator new inside a shared library is not reliable across libstdc++, so we
// route the memory that matters (the large, per-actor buffers) explicitly instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace vp {

using AllocFn = void* (*)(std::size_t size, std::size_t alignment, void* userContext);
using FreeFn = void (*)(void* memory, void* userContext);

// nullptr for both restores the default. Also installs the hooks into Bullet.
void setAllocator(AllocFn allocFn, FreeFn freeFn, void* userContext);

void* allocateBytes(std::size_t size, std::size_t alignment);
void freeBytes(void* memory);

// How many of Bullet's allocations the host's allocator has refused on this thread so far
// (they came from the system heap instead, allocator.cpp says why). A call that creates Bullet
// objects compares it before and after, and undoes its work when it grew.
uint64_t hostAllocationRefusals();

// Standard allocator over the hooks, 64-byte aligned so SIMD loads of any width are safe.
template <class T>
struct HookAllocator {
  using value_type = T;
  HookAllocator() noexcept = default;
  template <class U>
  HookAllocator(const HookAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    void* p = allocateBytes(n * sizeof(T), alignof(T) > 64 ? alignof(T) : 64);
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) noexcept { freeBytes(p); }
  template <class U>
  bool operator==(const HookAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const HookAllocator<U>&) const noexcept { return false; }
};

// The array type for simulation data.
template <class T>
using Array = std::vector<T, HookAllocator<T>>;

}  // namespace vp
