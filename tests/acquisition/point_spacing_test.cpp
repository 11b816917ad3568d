#include "acquisition/point_spacing.h"

#include "core/errors.h"
#include "sim/random.h"
#include "test_support.h"

#include <cmath>
#include <limits>
#include <vector>

namespace scanstation::acquisition {
namespace {

// Points in batches as a scan streams them: clustered (a crowd near one
// place, as the profiles near the top of an object), repeated exactly, and
// on the cube faces of the filter's grid.
std::vector<LaserScanPoints> streamed_points(std::uint64_t seed, double spacing) {
  sim::Random random(seed);
  std::vector<LaserScanPoints> batches;
  std::vector<Eigen::Vector3d> seen;
  for (int b = 0; b < 6; ++b) {
    const auto n = static_cast<Eigen::Index>(20 + random.below(60));
    LaserScanPoints batch;
    batch.cloud.positions.resize(n, 3);
    batch.cloud.colors.resize(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Vector3d p;
      const std::uint64_t kind = random.below(4);
      if (kind == 0 && !seen.empty()) {
        p = seen[random.below(seen.size())];  // a repeat
      } else if (kind == 1) {
        p = Eigen::Vector3d(random.uniform(), random.uniform(), random.uniform()) * 0.3 * spacing;  // the crowd
      } else if (kind == 2) {
        for (int k = 0; k < 3; ++k) p[k] = spacing * static_cast<double>(random.below(8));  // on the grid
      } else {
        p = Eigen::Vector3d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)) * 4 * spacing;
      }
      seen.push_back(p);
      batch.cloud.positions.row(i) = p.transpose();
      batch.cloud.colors.row(i).setConstant(static_cast<std::uint8_t>(i % 256));
      batch.confidence.push_back(static_cast<double>(i));
    }
    batches.push_back(batch);
  }
  return batches;
}

TEST(SpacingFilter, KeepsWhatTheGreedyReferenceKeepsAcrossBatches) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const double spacing = seed % 2 ? 0.5 : 3.0;
    const std::vector<LaserScanPoints> batches = streamed_points(seed, spacing);
    // Brute force: each point against every point kept before it.
    std::vector<Eigen::Vector3d> expected;
    for (const LaserScanPoints& batch : batches)
      for (Eigen::Index i = 0; i < batch.cloud.size(); ++i) {
        const Eigen::Vector3d p = batch.cloud.positions.row(i).transpose();
        bool near = false;
        for (const Eigen::Vector3d& q : expected) near = near || (q - p).norm() < spacing;
        if (!near) expected.push_back(p);
      }
    SpacingFilter filter(spacing);
    std::vector<Eigen::Vector3d> kept;
    Eigen::Index dropped = 0, total = 0;
    for (LaserScanPoints batch : batches) {
      total += batch.cloud.size();
      dropped += filter.thin(batch);
      ASSERT_EQ(batch.cloud.colors.rows(), batch.cloud.size());
      ASSERT_EQ(batch.confidence.size(), static_cast<std::size_t>(batch.cloud.size()));
      for (Eigen::Index i = 0; i < batch.cloud.size(); ++i) {
        // Colour and confidence stay with their point (both were its row).
        EXPECT_EQ(batch.cloud.colors(i, 0), static_cast<std::uint8_t>(static_cast<int>(batch.confidence[static_cast<std::size_t>(i)]) % 256));
        kept.push_back(batch.cloud.positions.row(i).transpose());
      }
    }
    ASSERT_EQ(kept.size(), expected.size()) << "seed " << seed;
    for (std::size_t k = 0; k < kept.size(); ++k) EXPECT_EQ(kept[k], expected[k]) << "seed " << seed;
    EXPECT_EQ(total - dropped, static_cast<Eigen::Index>(kept.size()));
    EXPECT_GT(dropped, 0);  // the repeats and the crowd at least
  }
}

TEST(SpacingFilter, ThinningTheThinnedStreamAgainKeepsEveryPoint) {
  // What a resumed scan relies on: its recorded steps come back thinned and
  // go through the live boundary's filter again.
  const std::vector<LaserScanPoints> batches = streamed_points(7, 1.0);
  SpacingFilter first(1.0), again(1.0);
  for (LaserScanPoints batch : batches) {
    first.thin(batch);
    const Eigen::Index n = batch.cloud.size();
    EXPECT_EQ(again.thin(batch), 0);
    EXPECT_EQ(batch.cloud.size(), n);
  }
}

TEST(SpacingFilter, ZeroKeepsEveryPointAndBadSpacingsOrPointsAreNamed) {
  LaserScanPoints batch = streamed_points(3, 1.0).front();
  const Eigen::MatrixX3d before = batch.cloud.positions;
  SpacingFilter none(0.0);
  EXPECT_EQ(none.thin(batch), 0);
  EXPECT_EQ(batch.cloud.positions, before);
  for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    test::expect_error<InvalidInput>([&] { SpacingFilter filter(bad); }, {"least point spacing", "≥ 0"});
  LaserScanPoints far;
  far.cloud.positions = Eigen::RowVector3d(1e9, 0, 0);
  EXPECT_EQ(SpacingFilter(1e-6).thin(far), 0);  // 1e15 spacings out: still numbered exactly
  far.cloud.positions = Eigen::RowVector3d(1e300, 0, 0);
  test::expect_error<InvalidInput>([&] { SpacingFilter(1e-3).thin(far); }, {"least point spacing", "2^62"});
  far.cloud.positions = Eigen::RowVector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  test::expect_error<InvalidInput>([&] { SpacingFilter(1.0).thin(far); }, {"least point spacing", "not finite"});
}

}  // namespace
}  // namespace scanstation::acquisition
