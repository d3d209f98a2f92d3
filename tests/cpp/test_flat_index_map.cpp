#include "common/flat_index_map.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_map>

using namespace mr;

namespace {

// Few distinct home slots, half of them the table's last ones: long probe runs that wrap
// around its end, where erasing must shift the right entries back.
struct CrowdingHash {
  size_t operator()(std::uint64_t k) const { return k % 2 ? ~size_t(0) - size_t(k % 5) : size_t(k % 4); }
};

template <class Map>
void expect_same(const Map& flat, const std::unordered_map<std::uint64_t, int>& reference, std::uint64_t keys) {
  ASSERT_EQ(flat.size(), reference.size());
  for (std::uint64_t k = 0; k < keys; ++k) {
    const int* v = flat.find(k);
    const auto it = reference.find(k);
    ASSERT_EQ(v != nullptr, it != reference.end()) << "key " << k;
    if (v) {
      EXPECT_EQ(*v, it->second) << "key " << k;
    }
  }
}

}  // namespace

TEST(FlatIndexMap, AssignAndEraseAgreeWithUnorderedMapUnderCrowdedProbes) {
  FlatIndexMap<std::uint64_t, CrowdingHash> flat;
  std::unordered_map<std::uint64_t, int> reference;
  std::mt19937 rng(7);
  constexpr std::uint64_t kKeys = 60;
  for (int step = 0; step < 20000; ++step) {
    const std::uint64_t key = rng() % kKeys;
    const int value = int(rng() % 1000);
    switch (rng() % 3) {
      case 0:
        flat.assign(key, value);
        reference[key] = value;
        break;
      case 1:
        EXPECT_EQ(flat.erase(key), reference.erase(key) > 0) << "step " << step;
        break;
      default: {
        const auto [stored, inserted] = flat.emplace(key, value);
        const auto [it, ref_inserted] = reference.emplace(key, value);
        EXPECT_EQ(inserted, ref_inserted);
        EXPECT_EQ(stored, it->second);
      }
    }
    if (step % 97 == 0) expect_same(flat, reference, kKeys);
  }
  expect_same(flat, reference, kKeys);
}

TEST(FlatIndexMap, EmptyTableFindsAndErasesNothing) {
  FlatIndexMap<std::uint64_t, CrowdingHash> flat;
  EXPECT_EQ(flat.find(3), nullptr);
  EXPECT_FALSE(flat.erase(3));
  flat.assign(3, 0);
  EXPECT_TRUE(flat.erase(3));
  EXPECT_EQ(flat.size(), 0u);
  EXPECT_EQ(flat.find(3), nullptr);
}
