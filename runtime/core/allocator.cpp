#include "core/allocator.h"

#include <LinearMath/btAlignedAllocator.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
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

// Bullet cannot take a refusal: it would construct its objects on NULL, and its constructors
// and containers are not written to unwind. When the host's allocator refuses a block Bullet
// asks for, the block comes from the system heap instead and the refusal is counted for the
// calling thread (hostAllocationRefusals()); creation calls then undo what they made and
// return OutOfMemory. Each block carries a header saying which heap it came from.
thread_local uint64_t t_refusals = 0;
constexpr std::size_t kHeaderAlignment = 16;  // holds the heap tag and the header's size
enum : uintptr_t { kFromHost = 0x686f7374, kFromSystem = 0x73797374 };

void* bulletAlignedAlloc(size_t size, int alignment) {
  const std::size_t pad = std::max<std::size_t>(static_cast<std::size_t>(alignment), kHeaderAlignment);
  uintptr_t heap = kFromHost;
  void* base = allocateBytes(size + pad, pad);
  if (base == nullptr) {
    ++t_refusals;
    heap = kFromSystem;
    base = std::aligned_alloc(pad, (size + pad + pad - 1) / pad * pad);
    if (base == nullptr) throw std::bad_alloc();
  }
  char* user = static_cast<char*>(base) + pad;
  reinterpret_cast<uintptr_t*>(user)[-1] = heap;
  reinterpret_cast<uintptr_t*>(user)[-2] = pad;
  return user;
}
void bulletAlignedFree(void* memory) {
  if (memory == nullptr) return;
  char* user = static_cast<char*>(memory);
  const uintptr_t heap = reinterpret_cast<uintptr_t*>(user)[-1];
  void* base = user - reinterpret_cast<uintptr_t*>(user)[-2];
  if (heap == kFromSystem) std::free(base);
  else freeBytes(base);
}
void* bulletAlloc(size_t size) { return bulletAlignedAlloc(size, static_cast<int>(kHeaderAlignment)); }
void bulletFree(void* memory) { bulletAlignedFree(memory); }

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

uint64_t hostAllocationRefusals() { return t_refusals; }

void* allocateBytes(std::size_t size, std::size_t alignment) {
  return g_alloc.load()(size, alignment, g_context.load());
}

void freeBytes(void* memory) {
  if (memory) g_free.load()(memory, g_context.load());
}

}  // namespace vp
