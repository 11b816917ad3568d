#include "smoothing/patch_adjacency.h"

#include <cstring>
#include <unordered_map>

namespace scanstation {

namespace {

struct CornerPair {
  double coordinates[6];
  bool operator==(const CornerPair& other) const {
    return std::memcmp(coordinates, other.coordinates, sizeof coordinates) == 0;
  }
};

struct CornerPairHash {
  std::size_t operator()(const CornerPair& key) const {
    std::size_t hash = 1469598103934665603ull;
    for (const double x : key.coordinates) {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      hash = (hash ^ bits) * 1099511628211ull;
    }
    return hash;
  }
};

CornerPair directed(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return {{from.x(), from.y(), from.z(), to.x(), to.y(), to.z()}};
}

}  // namespace

PatchAdjacency patch_adjacency(const BezierSurface& surface) {
  std::unordered_map<CornerPair, std::pair<int, int>, CornerPairHash> open;
  open.reserve(surface.patches.size() * 2);
  PatchAdjacency adjacency;
  for (int p = 0; p < static_cast<int>(surface.patches.size()); ++p)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& from = patch_corner(surface.patches[p], k);
      const Eigen::Vector3d& to = patch_corner(surface.patches[p], (k + 1) % 3);
      const auto partner = open.find(directed(to, from));
      if (partner != open.end()) {
        adjacency.pairs.push_back({partner->second.first, partner->second.second, p, k});
        open.erase(partner);
      } else {
        open.emplace(directed(from, to), std::make_pair(p, k));
      }
    }
  adjacency.unmatched = open.size();
  return adjacency;
}

}  // namespace scanstation
