#include "smoothing/patch_adjacency.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>

namespace scanstation {

namespace {

std::uint64_t point_hash(const Eigen::Vector3d& p) {
  std::uint64_t hash = 1469598103934665603ull;
  for (int i = 0; i < 3; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, &p[i], sizeof bits);
    hash = (hash ^ bits) * 1099511628211ull;
    hash ^= hash >> 29;
  }
  return hash;
}

bool same(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

// One patch edge: a hash of its two corners in either order, and 3·patch + edge.
struct HalfEdge {
  std::uint64_t key;
  std::uint32_t id;
};

// Least significant digit radix sort on the key's low kSortedBits, 11 bits
// a pass (linear time; stable, so equal keys keep the order of their ids).
// Partners only need to end up side by side, not the keys in order, and
// 2048 buckets a pass keep the scatter in cache (65536 made it a fifth of
// `smooth` on a 450k-patch surface).
constexpr int kDigitBits = 11;
constexpr int kSortedBits = 3 * kDigitBits;
constexpr std::uint64_t kSortedMask = (std::uint64_t{1} << kSortedBits) - 1;

template <class T>
using Scratch = std::vector<T, UninitialisedAllocator<T>>;  // every element written before it is read

void sort_by_key(Scratch<HalfEdge>& halves) {
  Scratch<HalfEdge> buffer(halves.size());
  std::vector<std::size_t> count(std::size_t{1} << kDigitBits);
  constexpr std::uint64_t digit = (std::uint64_t{1} << kDigitBits) - 1;
  for (int shift = 0; shift < kSortedBits; shift += kDigitBits) {
    std::fill(count.begin(), count.end(), 0);
    for (const HalfEdge& h : halves) ++count[(h.key >> shift) & digit];
    std::size_t offset = 0;
    for (std::size_t& c : count) offset += std::exchange(c, offset);
    for (const HalfEdge& h : halves) buffer[count[(h.key >> shift) & digit]++] = h;
    halves.swap(buffer);
  }
}

}  // namespace

PatchAdjacency patch_adjacency(const BezierSurface& surface) {
  // Sorting by a hash of the unordered corner pair brings partners together;
  // the corners are then compared bit for bit. partner[3p + k] is the partner
  // edge's id (or none), so the pairs come out in a fixed order: by the later
  // edge, as a scan over the patches would meet them.
  // The corners are copied out in patch order first, in the same pass that
  // hashes them: a patch spans several cache lines, and the comparisons in
  // hash order jump between patches (read from the patches themselves, the
  // comparisons were a quarter of `smooth` on a 450k-patch surface); the
  // copy puts an edge's two corners side by side, and the next group's are
  // fetched while this one is compared.
  const auto& patches = surface.patches;
  const std::uint32_t count = static_cast<std::uint32_t>(3 * patches.size());
  Scratch<Eigen::Vector3d> corner(count);
  Scratch<HalfEdge> halves(count);
  for (std::uint32_t p = 0; p < count / 3; ++p) {
    std::uint64_t hash[3];
    for (int k = 0; k < 3; ++k) {
      corner[3 * p + std::uint32_t(k)] = patch_corner(patches[p], k);
      hash[k] = point_hash(corner[3 * p + std::uint32_t(k)]);
    }
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t from = hash[k], to = hash[(k + 1) % 3];
      halves[3 * p + std::uint32_t(k)] = {(from + to) ^ ((from ^ to) * 0x9e3779b97f4a7c15ull >> 17), 3 * p + std::uint32_t(k)};
    }
  }
  const auto next = [](std::uint32_t id) { return id - id % 3 + (id % 3 + 1) % 3; };
  sort_by_key(halves);
  constexpr std::uint32_t none = ~0u;
  std::vector<std::uint32_t> partner(count, none);
  constexpr std::size_t kAhead = 16;  // half edges fetched ahead of the comparisons
  for (std::size_t begin = 0, end = 0; begin < halves.size(); begin = end) {
    for (std::size_t k = begin + kAhead; k < std::min(begin + kAhead + 2, halves.size()); ++k) {  // groups are pairs
      const std::uint32_t ahead = halves[k].id;
      __builtin_prefetch(&corner[ahead]);
      __builtin_prefetch(&corner[next(ahead)]);
      __builtin_prefetch(&partner[ahead]);
    }
    // A run of equal sorted bits holds every edge with the same key (and
    // rarely others, told apart by the rest of the key).
    while (end < halves.size() && ((halves[end].key ^ halves[begin].key) & kSortedMask) == 0) ++end;
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t a = halves[i].id;
      if (partner[a] != none) continue;
      for (std::size_t j = i + 1; j < end; ++j) {
        const std::uint32_t b = halves[j].id;
        if (partner[b] == none && halves[j].key == halves[i].key && same(corner[a], corner[next(b)]) &&
            same(corner[next(a)], corner[b])) {
          partner[a] = b;
          partner[b] = a;
          break;
        }
      }
    }
  }
  PatchAdjacency adjacency;
  adjacency.pairs.reserve(count / 2);
  for (std::uint32_t id = 0; id < count; ++id) {
    if (partner[id] == none)
      ++adjacency.unmatched;
    else if (partner[id] < id)
      adjacency.pairs.push_back({int(partner[id] / 3), int(partner[id] % 3), int(id / 3), int(id % 3)});
  }
  return adjacency;
}

}  // namespace scanstation
