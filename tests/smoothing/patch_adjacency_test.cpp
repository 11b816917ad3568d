#include "smoothing/patch_adjacency.h"

#include "sim/random.h"
#include "smoothing_test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <tuple>
#include <vector>

namespace scanstation {
namespace {

// A corner as its bits: the adjacency compares corners bit for bit.
using Bits = std::array<std::uint64_t, 3>;
Bits bits(const Eigen::Vector3d& p) {
  Bits b;
  std::memcpy(b.data(), p.data(), sizeof b);
  return b;
}

// The long way: every patch edge keyed by its corners, each matched with
// the first unmatched edge running the other way; pairs by the later edge.
PatchAdjacency brute_force(const BezierSurface& surface) {
  std::map<std::pair<Bits, Bits>, std::vector<int>> open;  // (from, to) → edges not matched yet
  std::vector<int> partner(3 * surface.patches.size(), -1);
  for (int id = 0; id < static_cast<int>(partner.size()); ++id) {
    const CubicTriangle& patch = surface.patches[static_cast<std::size_t>(id / 3)];
    const Bits from = bits(patch_corner(patch, id % 3)), to = bits(patch_corner(patch, (id % 3 + 1) % 3));
    auto reverse = open.find({to, from});
    if (reverse != open.end() && !reverse->second.empty()) {
      const int other = reverse->second.front();
      reverse->second.erase(reverse->second.begin());
      partner[static_cast<std::size_t>(id)] = other;
      partner[static_cast<std::size_t>(other)] = id;
    } else {
      open[{from, to}].push_back(id);
    }
  }
  PatchAdjacency a;
  for (int id = 0; id < static_cast<int>(partner.size()); ++id) {
    const int p = partner[static_cast<std::size_t>(id)];
    if (p < 0) ++a.unmatched;
    else if (p < id) a.pairs.push_back({p / 3, p % 3, id / 3, id % 3});
  }
  return a;
}

void expect_same(const PatchAdjacency& a, const PatchAdjacency& b) {
  EXPECT_EQ(a.unmatched, b.unmatched);
  ASSERT_EQ(a.pairs.size(), b.pairs.size());
  for (std::size_t i = 0; i < a.pairs.size(); ++i) {
    const auto key = [](const PatchEdgePair& p) { return std::tie(p.patch_a, p.edge_a, p.patch_b, p.edge_b); };
    EXPECT_EQ(key(a.pairs[i]), key(b.pairs[i])) << i;
  }
}


TEST(PatchAdjacency, ClosedSurfaceEveryEdgePairedAsTheLongWay) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const BezierSurface surface = test::six_split_surface(test::bumpy_sphere(seed, 0.1));
    const PatchAdjacency found = patch_adjacency(surface);
    EXPECT_EQ(found.unmatched, 0u) << seed;
    EXPECT_EQ(found.pairs.size(), 3 * surface.patches.size() / 2) << seed;
    expect_same(found, brute_force(surface));
  }
}

TEST(PatchAdjacency, OpenAndShuffledSurfaces) {
  const BezierSurface closed = test::six_split_surface(test::bumpy_sphere(4, 0.1));
  sim::Random random(5);
  BezierSurface open;
  for (const CubicTriangle& patch : closed.patches)
    if (random.uniform() < 0.7) open.patches.push_back(patch);  // holes everywhere
  const PatchAdjacency found = patch_adjacency(open);
  EXPECT_GT(found.unmatched, 0u);
  expect_same(found, brute_force(open));
  // An edge's corners equal except in the last bit pair with nothing.
  BezierSurface nudged = closed;
  auto& corner = nudged.patches[7][static_cast<std::size_t>(control_index(3, 0, 0))];
  corner.x() = std::nextafter(corner.x(), 10.0);
  const PatchAdjacency apart = patch_adjacency(nudged);
  EXPECT_EQ(apart.unmatched, 4u);  // the nudged corner's two edges and their two former partners
  expect_same(apart, brute_force(nudged));
  EXPECT_EQ(patch_adjacency(BezierSurface{}).pairs.size(), 0u);
}

}  // namespace
}  // namespace scanstation
