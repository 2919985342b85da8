#include "core/allocator.h"

#include <LinearMath/btAlignedAllocator.h>

#include <atomic>
#include <cstdlib>

namespace vp {
namespace {

void* defaultAlloc(std::size_t size, std::size_t alignment, void*) {
  // aligned_alloc wants size to be a multiple of the alignment.
  std::size_t rounded = (size + alignment - 1) / alignment * alignment;
  return std::aligned_alloc(alignment, rounded == 0 ? alignment : rounded);
}
void defaultFree(void* memory, void*) { std::free(memory); }

std::atomic<AllocFn> g_alloc{&defaultAlloc};
std::atomic<FreeFn> g_free{&defaultFree};
std::atomic<void*> g_context{nullptr};

void* bulletAlignedAlloc(size_t size, int alignment) {
  return allocateBytes(size, static_cast<std::size_t>(alignment));
}
void bulletAlignedFree(void* memory) { freeBytes(memory); }
void* bulletAlloc(size_t size) { return allocateBytes(size, 16); }
void bulletFree(void* memory) { freeBytes(memory); }

}  // namespace

void setAllocator(AllocFn allocFn, FreeFn freeFn, void* userContext) {
  bool custom = allocFn && freeFn;
  g_context.store(custom ? userContext : nullptr);
  g_alloc.store(custom ? allocFn : &defaultAlloc);
  g_free.store(custom ? freeFn : &defaultFree);
  if (custom) {
    btAlignedAllocSetCustomAligned(&bulletAlignedAlloc, &bulletAlignedFree);
    btAlignedAllocSetCustom(&bulletAlloc, &bulletFree);
  } else {
    btAlignedAllocSetCustomAligned(nullptr, nullptr);
    btAlignedAllocSetCustom(nullptr, nullptr);
  }
}

void* allocateBytes(std::size_t size, std::size_t alignment) {
  return g_alloc.load()(size, alignment, g_context.load());
}

void freeBytes(void* memory) {
  if (memory) g_free.load()(memory, g_context.load());
}

}  // namespace vp
