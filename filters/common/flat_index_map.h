// A hash map from small keys to non-negative ints, stored in two flat arrays with
// linear probing. For the big lookup tables of one run (a point per hash bucket, an
// edge-face crossing per key): std::unordered_map allocates a node per entry, and at
// a million entries the allocations, the cache misses and freeing them at the end
// cost more than the lookups. The order of insertion is not kept. Erasing shifts the
// rest of a probe run back (no tombstones), so a table whose entries come and go (the
// remesher's side -> face table through its edge swaps) stays as fast as a fresh one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace mr {

/// A hash for 64-bit keys packed from two indices (edges, sides, grid cells): the slot is
/// taken from the low bits, which the plain key would crowd into a few runs.
struct PackedKeyHash {
  size_t operator()(std::uint64_t k) const {
    const std::uint64_t h = k * 0x9E3779B97F4A7C15ull;
    return size_t(h ^ (h >> 31));
  }
};

template <class Key, class Hash = PackedKeyHash>
class FlatIndexMap {
public:
  /// Room for n entries without growing.
  void reserve(size_t n) {
    size_t cap = 16;
    while (cap < 2 * n) cap *= 2;
    if (cap > value_.size()) rehash(cap);
  }

  size_t size() const { return size_; }

  /// The value of `key`, or nullptr.
  const int* find(const Key& key) const {
    if (size_ == 0) return nullptr;
    for (size_t i = slot(key);; i = (i + 1) & mask_) {
      if (value_[i] < 0) return nullptr;
      if (key_[i] == key) return &value_[i];
    }
  }

  /// Inserts (key, value) if key is absent. Returns the stored value and whether it
  /// was inserted. `value` must be >= 0 (a negative value marks an empty slot).
  std::pair<int, bool> emplace(const Key& key, int value) {
    if (2 * (size_ + 1) > value_.size()) rehash(value_.empty() ? 16 : 2 * value_.size());
    size_t i = slot(key);
    for (; value_[i] >= 0; i = (i + 1) & mask_)
      if (key_[i] == key) return {value_[i], false};
    key_[i] = key;
    value_[i] = value;
    ++size_;
    return {value, true};
  }

  /// Sets the value of `key`, inserting it if absent. `value` must be >= 0.
  void assign(const Key& key, int value) {
    if (2 * (size_ + 1) > value_.size()) rehash(value_.empty() ? 16 : 2 * value_.size());
    size_t i = slot(key);
    for (; value_[i] >= 0; i = (i + 1) & mask_)
      if (key_[i] == key) {
        value_[i] = value;
        return;
      }
    key_[i] = key;
    value_[i] = value;
    ++size_;
  }

  /// Removes `key`; false if it was absent.
  bool erase(const Key& key) {
    if (size_ == 0) return false;
    size_t gap = slot(key);
    for (;; gap = (gap + 1) & mask_) {
      if (value_[gap] < 0) return false;
      if (key_[gap] == key) break;
    }
    // Entries after the gap in its probe run move into it unless their home slot lies
    // cyclically in (gap, j]: every entry stays reachable from its home without a marker.
    for (size_t j = (gap + 1) & mask_; value_[j] >= 0; j = (j + 1) & mask_) {
      const size_t home = slot(key_[j]);
      const bool stays = gap <= j ? (gap < home && home <= j) : (gap < home || home <= j);
      if (stays) continue;
      key_[gap] = key_[j];
      value_[gap] = value_[j];
      gap = j;
    }
    value_[gap] = -1;
    --size_;
    return true;
  }

private:
  size_t slot(const Key& key) const { return Hash{}(key) & mask_; }

  void rehash(size_t cap) {
    std::vector<Key> keys(cap);
    std::vector<int> values(cap, -1);
    const size_t mask = cap - 1;
    for (size_t j = 0; j < value_.size(); ++j) {
      if (value_[j] < 0) continue;
      size_t i = Hash{}(key_[j]) & mask;
      while (values[i] >= 0) i = (i + 1) & mask;
      keys[i] = key_[j];
      values[i] = value_[j];
    }
    key_.swap(keys);
    value_.swap(values);
    mask_ = mask;
  }

  std::vector<Key> key_;
  std::vector<int> value_;
  size_t mask_ = 0;
  size_t size_ = 0;
};

}  // namespace mr
