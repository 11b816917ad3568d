#include "core/unique_points.h"

#include <array>
#include <bit>
#include <cstdint>

namespace scanstation {

namespace {

/// Bits of a coordinate compared by value: adding 0.0 turns −0.0 into +0.0.
std::uint64_t value_bits(double x) { return std::bit_cast<std::uint64_t>(x + 0.0); }

/// A fixed mix of the three coordinates' bits (splitmix64 finaliser), so the
/// table's probe sequences, and with them nothing observable, depend only on
/// the input.
std::uint64_t mix(std::uint64_t h) {
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

}  // namespace

Eigen::Index unique_points(const Eigen::MatrixX3d& P, std::vector<Eigen::Index>& first, std::vector<Eigen::Index>& map) {
  const Eigen::Index n = P.rows();
  // One pass in input order with an open-addressing table from a position to
  // its slot in `first`: the first occurrence claims the slot, so `first`
  // comes out increasing without a sort (sorting 1M points took about twice as long).
  std::size_t capacity = 16;
  while (capacity < 2 * static_cast<std::size_t>(n)) capacity *= 2;
  // Each entry keeps the position's full hash beside its slot, so a probe
  // reads the points only when the hashes agree (in practice: a duplicate).
  struct Entry {
    std::uint64_t hash;
    Eigen::Index slot = -1;
  };
  std::vector<Entry> table(capacity);
  const auto key = [&](Eigen::Index i) {
    return std::array<std::uint64_t, 3>{value_bits(P(i, 0)), value_bits(P(i, 1)), value_bits(P(i, 2))};
  };
  first.clear();
  map.assign(static_cast<std::size_t>(n), 0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = key(i);
    const std::uint64_t hash = mix(k[0] ^ mix(k[1] ^ mix(k[2])));
    std::size_t at = hash & (capacity - 1);
    while (table[at].slot >= 0 && (table[at].hash != hash || key(first[static_cast<std::size_t>(table[at].slot)]) != k))
      at = (at + 1) & (capacity - 1);
    if (table[at].slot < 0) {
      table[at] = {hash, static_cast<Eigen::Index>(first.size())};
      first.push_back(i);
    }
    map[static_cast<std::size_t>(i)] = table[at].slot;
  }
  return n - static_cast<Eigen::Index>(first.size());
}

}  // namespace scanstation
