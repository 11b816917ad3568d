// The 2D insertion order: Hilbert indices and BRIO rounds.
#include "reconstruct/spatial_order.h"
#include "sim/random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

namespace scanstation {
namespace {

using Point = CGAL::Epick::Point_2;
using sim::Random;

// The Hilbert index by the textbook loop: one level at a time, the
// coordinates themselves turned and mirrored into the quadrant's frame.
std::uint64_t textbook_hilbert(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t side = 1u << 28;
  std::uint64_t d = 0;
  for (std::uint32_t s = side / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = side - 1 - x;
        y = side - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

TEST(HilbertIndex2, MatchesTheTextbookLoop) {
  Random random(11);
  for (int trial = 0; trial < 20000; ++trial) {
    const auto x = static_cast<std::uint32_t>(random.uniform(0.0, 1.0) * (1u << 28));
    const auto y = static_cast<std::uint32_t>(random.uniform(0.0, 1.0) * (1u << 28));
    ASSERT_EQ(hilbert_index_2(x, y), textbook_hilbert(x, y)) << x << ", " << y;
  }
  EXPECT_EQ(hilbert_index_2(0, 0), 0u);
  EXPECT_EQ(hilbert_index_2((1u << 28) - 1, 0), (std::uint64_t{1} << 56) - 1);
}

TEST(HilbertIndex2, VisitsEveryCellOfACoarseGridOnceThroughNeighbours) {
  constexpr int side = 64, shift = 28 - 6;
  std::vector<std::pair<std::uint64_t, std::pair<int, int>>> cells;
  for (int x = 0; x < side; ++x)
    for (int y = 0; y < side; ++y)
      cells.push_back({hilbert_index_2(static_cast<std::uint32_t>(x) << shift, static_cast<std::uint32_t>(y) << shift), {x, y}});
  std::sort(cells.begin(), cells.end());
  for (std::size_t i = 1; i < cells.size(); ++i) {
    ASSERT_LT(cells[i - 1].first, cells[i].first);
    const auto [x0, y0] = cells[i - 1].second;
    const auto [x1, y1] = cells[i].second;
    ASSERT_EQ(std::abs(x1 - x0) + std::abs(y1 - y0), 1) << "a jump after cell " << i - 1;
  }
}

// A Hilbert curve visits the cells of every level's grid once each, each
// next to the last: along the coarse grid of the top 4 levels (cells at
// multiples of 2^15) and along the first 16³ cells at the finest level.
TEST(HilbertIndex3, VisitsEveryCellOfACoarseAndAFineGridOnceThroughNeighbours) {
  for (const int shift : {19 - 4, 0}) {
    std::vector<std::pair<std::uint64_t, std::array<int, 3>>> cells;
    for (int x = 0; x < 16; ++x)
      for (int y = 0; y < 16; ++y)
        for (int z = 0; z < 16; ++z)
          cells.push_back({hilbert_index_3(static_cast<std::uint32_t>(x) << shift, static_cast<std::uint32_t>(y) << shift,
                                           static_cast<std::uint32_t>(z) << shift),
                           {x, y, z}});
    std::sort(cells.begin(), cells.end());
    EXPECT_EQ(cells.front().second, (std::array<int, 3>{0, 0, 0}));
    for (std::size_t i = 1; i < cells.size(); ++i) {
      ASSERT_LT(cells[i - 1].first, cells[i].first) << "shift " << shift;
      int steps = 0;
      for (int k = 0; k < 3; ++k) steps += std::abs(cells[i].second[k] - cells[i - 1].second[k]);
      ASSERT_EQ(steps, 1) << "a jump after cell " << i - 1 << ", shift " << shift;
    }
    if (shift == 0) {
      EXPECT_EQ(cells.back().first, 4095u);  // the first 16³ cells of the curve
    }
  }
}

// Integer points in [0, 1023]² with both corners present: the sort's grid
// then puts coordinate x on grid line x · 2^18 exactly.
std::vector<std::pair<Point, int>> grid_points(int n, std::uint64_t seed, double scale) {
  Random random(seed);
  std::vector<std::pair<Point, int>> points = {{Point(0, 0), 0}, {Point(1023 * scale, 1023 * scale), 1}};
  for (int i = 2; i < n; ++i)
    points.push_back({Point(std::floor(random.uniform(0.0, 1024.0)) * scale, std::floor(random.uniform(0.0, 1024.0)) * scale), i});
  return points;
}

std::uint64_t grid_index(const Point& p, double scale) {
  return hilbert_index_2(static_cast<std::uint32_t>(p.x() / scale) << 18, static_cast<std::uint32_t>(p.y() / scale) << 18);
}

// The Morton index interleaves the coordinates' bits, x highest: against
// the bit-by-bit definition on random coordinates of up to 21 bits.
TEST(MortonIndex3, InterleavesTheBitsXFirst) {
  sim::Random random(3);
  for (int trial = 0; trial < 1000; ++trial) {
    const auto coordinate = [&] { return static_cast<std::uint32_t>(random.below(1u << 21)); };
    const std::uint32_t x = coordinate(), y = coordinate(), z = coordinate();
    std::uint64_t expected = 0;
    for (int bit = 20; bit >= 0; --bit)
      expected = expected << 3 | (x >> bit & 1u) << 2 | (y >> bit & 1u) << 1 | (z >> bit & 1u);
    EXPECT_EQ(morton_index_3(x, y, z), expected) << x << " " << y << " " << z;
  }
}

TEST(BrioHilbertSort, RoundsOfAQuarterEachFollowTheCurve) {
  constexpr int n = 100000;
  auto points = grid_points(n, 5, 1.0);
  brio_hilbert_sort(points);
  std::vector<char> seen(n, 0);
  for (const auto& [p, index] : points) {
    ASSERT_FALSE(seen[static_cast<std::size_t>(index)]) << "index " << index << " twice";
    seen[static_cast<std::size_t>(index)] = 1;
  }
  // Runs along the curve (an equal cell keeps index order): one per round,
  // 8 rounds for 100k points (100000 / 4^7 ≤ 16), the last of three quarters.
  std::vector<std::size_t> run_starts = {0};
  for (std::size_t i = 1; i < points.size(); ++i) {
    const auto a = grid_index(points[i - 1].first, 1.0), b = grid_index(points[i].first, 1.0);
    if (b < a || (a == b && points[i].second < points[i - 1].second)) run_starts.push_back(i);
  }
  EXPECT_LE(run_starts.size(), 8u);
  EXPECT_GE(run_starts.size(), 6u);
  const double last = static_cast<double>(n - run_starts.back()) / n;
  EXPECT_NEAR(last, 0.75, 0.01);
  const double before_last = static_cast<double>(run_starts.back() - run_starts[run_starts.size() - 2]) / n;
  EXPECT_NEAR(before_last, 0.1875, 0.01);
}

TEST(BrioHilbertSort, PowerOfTwoScalesAndRepeatsKeepTheOrder) {
  constexpr int n = 20000;
  auto reference = grid_points(n, 9, 1.0);
  brio_hilbert_sort(reference);
  for (const double scale : {std::ldexp(1.0, -1040), std::ldexp(1.0, -300), std::ldexp(1.0, 1000)}) {
    auto points = grid_points(n, 9, scale);
    brio_hilbert_sort(points);
    for (int i = 0; i < n; ++i) ASSERT_EQ(points[static_cast<std::size_t>(i)].second, reference[static_cast<std::size_t>(i)].second) << scale;
  }
  auto again = grid_points(n, 9, 1.0);
  brio_hilbert_sort(again);
  for (int i = 0; i < n; ++i) ASSERT_EQ(again[static_cast<std::size_t>(i)].second, reference[static_cast<std::size_t>(i)].second);
}

// One far outlier squeezes the rest of the points into a few cells of the
// grid over the whole box; those cells are ordered again on grids of their
// own, so consecutive points of the last round stay close (in input order,
// random here, they would lie half the cluster apart on average).
template <typename Point>
double mean_step_in_last_round(std::vector<std::pair<Point, int>> points) {
  brio_hilbert_sort(points);
  double sum = 0;
  std::size_t steps = 0;
  for (std::size_t i = points.size() / 4 + 1; i < points.size(); ++i) {
    const auto& a = points[i - 1].first;
    const auto& b = points[i].first;
    if (a.x() > 1e3 || b.x() > 1e3) continue;  // the outlier
    sum += std::sqrt(CGAL::squared_distance(a, b));
    ++steps;
  }
  return sum / static_cast<double>(steps);
}

TEST(BrioHilbertSort, AFarOutlierLeavesTheClusterInSpatialOrder) {
  Random random(21);
  std::vector<std::pair<CGAL::Epick::Point_3, int>> cloud;
  for (int i = 0; i < 20000; ++i)
    cloud.push_back({CGAL::Epick::Point_3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)), i});
  cloud.push_back({CGAL::Epick::Point_3(1e7, 0, 0), 20000});
  EXPECT_LT(mean_step_in_last_round(cloud), 0.15);  // the cluster's spacing is about 0.07; random order: 1.3
  std::vector<std::pair<Point, int>> flat;
  for (int i = 0; i < 20000; ++i) flat.push_back({Point(random.uniform(-1, 1) * 1e-9, random.uniform(-1, 1) * 1e-9), i});
  flat.push_back({Point(1e7, 0), 20000});
  EXPECT_LT(mean_step_in_last_round(flat), 1e-10);  // spacing about 1.4e-11; random order: 1.0e-9
}

TEST(BrioHilbertSort, EqualPointsAndNaNAreOrderedWithoutFuss) {
  std::vector<std::pair<Point, int>> same;
  for (int i = 0; i < 1000; ++i) same.push_back({Point(2.5, -1), i});
  same.push_back({Point(std::nan(""), 0), 1000});
  brio_hilbert_sort(same);
  std::set<int> indices;
  for (const auto& [p, index] : same) indices.insert(index);
  EXPECT_EQ(indices.size(), 1001u);
}

}  // namespace
}  // namespace scanstation
