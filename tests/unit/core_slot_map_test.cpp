#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <utility>

#include "core/slot_map.h"

namespace vp {
namespace {

TEST(SlotMap, InsertGetRemove) {
  SlotMap<int> map;
  auto a = map.insert(std::make_unique<int>(7));
  auto b = map.insert(std::make_unique<int>(9));
  ASSERT_NE(a.index1, 0u);
  EXPECT_EQ(*map.get(a.index1, a.generation), 7);
  EXPECT_EQ(*map.get(b.index1, b.generation), 9);
  EXPECT_EQ(map.size(), 2u);
  EXPECT_NE(map.remove(a.index1, a.generation), nullptr);
  EXPECT_EQ(map.get(a.index1, a.generation), nullptr);
  EXPECT_EQ(map.remove(a.index1, a.generation), nullptr);  // double remove is refused
  EXPECT_EQ(map.size(), 1u);
}

TEST(SlotMap, ReusedSlotDoesNotResolveOldHandle) {
  SlotMap<int> map;
  auto a = map.insert(std::make_unique<int>(1));
  map.remove(a.index1, a.generation);
  auto b = map.insert(std::make_unique<int>(2));
  EXPECT_EQ(b.index1, a.index1);  // LIFO reuse
  EXPECT_NE(b.generation, a.generation);
  EXPECT_EQ(map.get(a.index1, a.generation), nullptr);
  EXPECT_EQ(*map.get(b.index1, b.generation), 2);
}

TEST(SlotMap, NullAndOutOfRangeHandles) {
  SlotMap<int> map;
  map.insert(std::make_unique<int>(1));
  EXPECT_EQ(map.get(0, 0), nullptr);
  EXPECT_EQ(map.get(0, 1), nullptr);
  EXPECT_EQ(map.get(5, 1), nullptr);
  EXPECT_EQ(map.get(1, 0), nullptr);
}

// A slot whose generations are used up is retired: no (slot, generation) pair comes back.
TEST(SlotMap, ExhaustedSlotIsRetiredNotWrapped) {
  SlotMap<int> map;
  map.setGenerationLimit(4);
  std::set<std::pair<uint32_t, uint32_t>> issued;
  for (int i = 0; i < 10; ++i) {
    auto h = map.insert(std::make_unique<int>(i));
    EXPECT_NE(h.generation, 0u);
    EXPECT_LT(h.generation, 4u);
    EXPECT_TRUE(issued.insert({h.index1, h.generation}).second) << "(" << h.index1 << ", " << h.generation << ") again";
    map.remove(h.index1, h.generation);
  }
  // Generations 1..3 per slot: ten objects one at a time used slots 1..4.
  EXPECT_EQ(map.capacity(), 4u);
  EXPECT_TRUE(map.canInsert(4));
  while (map.capacity() < 4 || map.canInsert(4)) {
    auto h = map.insert(std::make_unique<int>(0));
    map.remove(h.index1, h.generation);
  }
  EXPECT_FALSE(map.canInsert(4));  // every slot retired
}

}  // namespace
}  // namespace vp
