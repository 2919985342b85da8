// Generational slot map: the storage behind every id the C ABI hands out.
//
// An id is (index + 1, generation). Destroying an object bumps its slot's generation, so an
// old id stops resolving instead of aliasing whatever reuses the slot. No (slot, generation)
// pair is ever issued twice: a slot whose generation would pass the limit is retired rather
// than wrapped. Generation 0 is never issued, so an all-zero id is always null. Free slots are
// reused LIFO.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

namespace vp {

template <class T>
class SlotMap {
 public:
  struct Handle {
    uint32_t index1 = 0;
    uint32_t generation = 0;
  };

  // Takes ownership; returns the new handle.
  Handle insert(std::unique_ptr<T> value) {
    uint32_t slot;
    if (!freeSlots_.empty()) {
      slot = freeSlots_.back();
      freeSlots_.pop_back();
    } else {
      slot = static_cast<uint32_t>(slots_.size());
      slots_.push_back(Slot{});
    }
    slots_[slot].value = std::move(value);
    ++liveCount_;
    return Handle{slot + 1, slots_[slot].generation};
  }

  T* get(uint32_t index1, uint32_t generation) const {
    if (index1 == 0 || index1 > slots_.size()) return nullptr;
    const Slot& s = slots_[index1 - 1];
    if (s.generation != generation || !s.value) return nullptr;
    return s.value.get();
  }

  // Returns the removed object (nullptr if the handle did not resolve).
  std::unique_ptr<T> remove(uint32_t index1, uint32_t generation) {
    if (!get(index1, generation)) return nullptr;
    Slot& s = slots_[index1 - 1];
    std::unique_ptr<T> out = std::move(s.value);
    ++s.generation;
    const bool exhausted = s.generation == generationLimit_ || s.generation == 0;
    if (!exhausted) freeSlots_.push_back(index1 - 1);
    --liveCount_;
    return out;
  }

  std::size_t size() const { return liveCount_; }
  std::size_t capacity() const { return slots_.size(); }
  // Whether insert() can hand out a handle whose index fits in maxSlots slots.
  bool canInsert(std::size_t maxSlots) const { return !freeSlots_.empty() || slots_.size() < maxSlots; }

  // Visits live objects in slot order (deterministic for a given history of inserts/removes).
  template <class F>
  void forEach(F&& visit) const {
    for (std::size_t i = 0; i < slots_.size(); ++i)
      if (slots_[i].value) visit(Handle{static_cast<uint32_t>(i + 1), slots_[i].generation}, *slots_[i].value);
  }

  // Ids whose generation field is narrower than 32 bits (vpWorldId uses 16; child ids keep
  // their top bits for their kind) set this so generations fit: they stay below it.
  void setGenerationLimit(uint32_t limit) { generationLimit_ = limit; }

 private:
  struct Slot {
    std::unique_ptr<T> value;
    uint32_t generation = 1;
  };
  std::vector<Slot> slots_;
  std::vector<uint32_t> freeSlots_;
  std::size_t liveCount_ = 0;
  uint32_t generationLimit_ = 0;  // 0: up to 2^32 - 1
};

}  // namespace vp
