// Open addressing from 64-bit keys to small values, for the hot lookups of
// the boundary surface's grid cells:
// multiplicative hashing, linear probing, no erase (callers reset a value
// instead). Keys must leave bit 63 clear (all ones marks an empty slot).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace scanstation {

template <typename V>
class U64Map {
 public:
  /// expected: how many keys to make room for before the first growth
  explicit U64Map(std::size_t expected = 0) {
    std::size_t capacity = 16;
    while (capacity < 2 * expected) capacity *= 2;
    keys_.assign(capacity, kEmpty);
    values_.assign(capacity, V{});
  }
  const V* find(std::uint64_t k) const {
    const std::size_t s = slot(k);
    return keys_[s] == kEmpty ? nullptr : &values_[s];
  }
  /// The value of k, V{} when new.
  V& operator[](std::uint64_t k) {
    std::size_t s = slot(k);
    if (keys_[s] == kEmpty) {
      if (2 * (used_ + 1) > keys_.size()) {
        grow();
        s = slot(k);
      }
      keys_[s] = k;
      ++used_;
    }
    return values_[s];
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::size_t slot(std::uint64_t k) const {
    const std::size_t mask = keys_.size() - 1;
    std::size_t s = static_cast<std::size_t>((k * 0x9E3779B97F4A7C15ULL) >> 17) & mask;
    while (keys_[s] != kEmpty && keys_[s] != k) s = (s + 1) & mask;
    return s;
  }
  void grow() {
    std::vector<std::uint64_t> keys = std::move(keys_);
    std::vector<V> values = std::move(values_);
    keys_.assign(keys.size() * 2, kEmpty);
    values_.assign(keys.size() * 2, V{});
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) {
        const std::size_t s = slot(keys[i]);
        keys_[s] = keys[i];
        values_[s] = std::move(values[i]);
      }
  }
  std::vector<std::uint64_t> keys_;
  std::vector<V> values_;
  std::size_t used_ = 0;
};

}  // namespace scanstation
