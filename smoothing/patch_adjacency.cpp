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

// Least significant digit radix sort on the key, 16 bits a pass (linear
// time; stable, so equal keys keep the order of their ids).
void sort_by_key(std::vector<HalfEdge>& halves) {
  std::vector<HalfEdge> buffer(halves.size());
  std::vector<std::size_t> count(1 << 16);
  for (int shift = 0; shift < 64; shift += 16) {
    std::fill(count.begin(), count.end(), 0);
    for (const HalfEdge& h : halves) ++count[(h.key >> shift) & 0xffff];
    std::size_t offset = 0;
    for (std::size_t& c : count) offset += std::exchange(c, offset);
    for (const HalfEdge& h : halves) buffer[count[(h.key >> shift) & 0xffff]++] = h;
    halves.swap(buffer);
  }
}

}  // namespace

PatchAdjacency patch_adjacency(const BezierSurface& surface) {
  // Sorting by a hash of the unordered corner pair brings partners together;
  // the corners are then compared bit for bit. partner[3p + k] is the partner
  // edge's id (or none), so the pairs come out in a fixed order: by the later
  // edge, as a scan over the patches would meet them.
  const auto& patches = surface.patches;
  const std::uint32_t count = static_cast<std::uint32_t>(3 * patches.size());
  std::vector<HalfEdge> halves(count);
  std::vector<std::uint64_t> corner_hash(count);
  for (std::uint32_t id = 0; id < count; ++id) corner_hash[id] = point_hash(patch_corner(patches[id / 3], id % 3));
  for (std::uint32_t id = 0; id < count; ++id) {
    const std::uint64_t from = corner_hash[id], to = corner_hash[id - id % 3 + (id % 3 + 1) % 3];
    halves[id] = {(from + to) ^ ((from ^ to) * 0x9e3779b97f4a7c15ull >> 17), id};
  }
  corner_hash = {};
  sort_by_key(halves);
  constexpr std::uint32_t none = ~0u;
  std::vector<std::uint32_t> partner(count, none);
  const auto from = [&](std::uint32_t id) -> const Eigen::Vector3d& { return patch_corner(patches[id / 3], id % 3); };
  const auto to = [&](std::uint32_t id) -> const Eigen::Vector3d& {
    return patch_corner(patches[id / 3], (id % 3 + 1) % 3);
  };
  for (std::size_t begin = 0, end = 0; begin < halves.size(); begin = end) {
    while (end < halves.size() && halves[end].key == halves[begin].key) ++end;
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t a = halves[i].id;
      if (partner[a] != none) continue;
      for (std::size_t j = i + 1; j < end; ++j) {
        const std::uint32_t b = halves[j].id;
        if (partner[b] == none && same(from(a), to(b)) && same(to(a), from(b))) {
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
