#include "acquisition/laser_line.h"
#include "acquisition/laser_triangulation.h"
#include "acquisition/outlier_removal.h"
#include "core/errors.h"
#include "sim/random.h"
#include "test_support.h"

#include <cmath>

namespace scanstation::acquisition {
namespace {

// A frame pair with a Gaussian stripe of standard deviation `sigma` whose
// centre in row r is centre(r), over a textured background.
template <class Centre>
std::pair<cv::Mat, cv::Mat> stripe_pair(Centre centre, double sigma, double height, double noise, std::uint64_t seed) {
  cv::Mat on(64, 200, CV_8U), off(64, 200, CV_8U);
  sim::Random random(seed);
  for (int r = 0; r < on.rows; ++r)
    for (int c = 0; c < on.cols; ++c) {
      const double background = 60 + 30 * std::sin(0.1 * c + 0.2 * r);
      const double u = (c - centre(r)) / sigma;
      const auto level = [](double v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0l, 255l)); };
      off.at<std::uint8_t>(r, c) = level(background + noise * random.normal());
      on.at<std::uint8_t>(r, c) = level(background + height * std::exp(-0.5 * u * u) + noise * random.normal());
    }
  return {on, off};
}

double centre_of_row(int r) { return 80.0 + 0.37 * r; }

TEST(LaserLine, SubPixelCentresOfAGaussianStripe) {
  const auto [on, off] = stripe_pair(centre_of_row, 1.3, 150, 0.0, 1);
  for (const auto& [fit, tolerance] : {std::pair{PeakFit::gaussian, 0.03}, std::pair{PeakFit::centre_of_mass, 0.06},
                                      std::pair{PeakFit::parabolic, 0.15}}) {
    LaserLineOptions options;
    options.fit = fit;
    const LaserLine line = extract_laser_line(on, off, options);
    ASSERT_EQ(line.peaks.size(), 64u);
    double worst = 0;
    for (const LinePeak& p : line.peaks) {
      worst = std::max(worst, std::abs(p.x - centre_of_row(static_cast<int>(p.y))));
      EXPECT_GT(p.confidence, 0.0f);
      EXPECT_LE(p.confidence, 1.0f);
    }
    EXPECT_LT(worst, tolerance) << static_cast<int>(fit);
  }
}

TEST(LaserLine, ThresholdFollowsTheNoiseAndRejectsFaintStripes) {
  const auto [on, off] = stripe_pair(centre_of_row, 1.3, 150, 3.0, 2);
  const LaserLine line = extract_laser_line(on, off);
  EXPECT_NEAR(line.noise_sigma, 3.0 * std::sqrt(2.0), 1.0);
  EXPECT_NEAR(line.threshold, 6.0 * line.noise_sigma, 1.0);
  EXPECT_GE(line.peaks.size(), 62u);
  for (const LinePeak& p : line.peaks) EXPECT_LT(std::abs(p.x - centre_of_row(static_cast<int>(p.y))), 0.3);
  // A stripe below the threshold gives nothing, not noise peaks.
  const auto [faint_on, faint_off] = stripe_pair(centre_of_row, 1.3, 12, 3.0, 3);
  EXPECT_LT(extract_laser_line(faint_on, faint_off).peaks.size(), 3u);
}

TEST(LaserLine, RejectsWideSaturatedAndDoublePeaks) {
  const auto [wide_on, wide_off] = stripe_pair(centre_of_row, 8.0, 150, 0.0, 4);
  EXPECT_TRUE(extract_laser_line(wide_on, wide_off).peaks.empty());
  const auto [hot_on, hot_off] = stripe_pair(centre_of_row, 1.3, 400, 0.0, 5);
  EXPECT_TRUE(extract_laser_line(hot_on, hot_off).peaks.empty());
  const auto [two_on, two_off] = stripe_pair([](int) { return 60.0; }, 1.3, 150, 0.0, 6);
  const auto [other_on, other_off] = stripe_pair([](int) { return 140.0; }, 1.3, 120, 0.0, 6);
  cv::Mat both = cv::max(two_on, other_on);
  EXPECT_TRUE(extract_laser_line(both, two_off).peaks.empty());
  // A weak reflection (below the ratio) does not hide the stripe.
  const auto [weak_on, weak_off] = stripe_pair([](int) { return 140.0; }, 1.3, 40, 0.0, 6);
  EXPECT_EQ(extract_laser_line(cv::max(two_on, weak_on), two_off).peaks.size(), 64u);
}

TEST(LaserLine, RegionOfInterestLimitsTheSearch) {
  const auto [on, off] = stripe_pair(centre_of_row, 1.3, 150, 0.0, 7);
  LaserLineOptions options;
  options.region = cv::Rect(0, 10, 100, 20);  // the stripe leaves x < 100 at row 54
  const LaserLine line = extract_laser_line(on, off, options);
  ASSERT_EQ(line.peaks.size(), 20u);
  EXPECT_EQ(line.peaks.front().y, 10);
  options.region = cv::Rect(150, 0, 100, 10);
  test::expect_error<InvalidInput>([&] { extract_laser_line(on, off, options); }, {"outside the frame"});
  test::expect_error<InvalidInput>([&] { extract_laser_line(on, off(cv::Rect(0, 0, 10, 10))); }, {"differ in size"});
  cv::Mat colour;
  cv::merge(std::vector<cv::Mat>{on, on, on}, colour);
  test::expect_error<InvalidInput>([&] { extract_laser_line(colour, colour); }, {"8-bit single-channel"});
}

// A horizontal stripe (the transposed pair), searched per column: the same
// sub-pixel accuracy as the row search, now in y.
TEST(LaserLine, SubPixelCentresOfAHorizontalStripePerColumn) {
  const auto [on, off] = stripe_pair(centre_of_row, 1.3, 150, 0.0, 1);
  cv::Mat on_t, off_t;
  cv::transpose(on, on_t);
  cv::transpose(off, off_t);
  for (const auto& [fit, tolerance] : {std::pair{PeakFit::gaussian, 0.03}, std::pair{PeakFit::centre_of_mass, 0.06},
                                      std::pair{PeakFit::parabolic, 0.15}}) {
    LaserLineOptions options;
    options.fit = fit;
    options.stripe = StripeDirection::horizontal;
    const LaserLine line = extract_laser_line(on_t, off_t, options);
    ASSERT_EQ(line.peaks.size(), 64u);
    double worst = 0;
    for (std::size_t i = 0; i < line.peaks.size(); ++i) {
      const LinePeak& p = line.peaks[i];
      EXPECT_EQ(p.x, static_cast<double>(i));  // column order
      worst = std::max(worst, std::abs(p.y - centre_of_row(static_cast<int>(p.x))));
    }
    EXPECT_LT(worst, tolerance) << static_cast<int>(fit);
  }
}

// Column search on the transposed frames = row search on the frames, peak for
// peak, with noisy frames, rejections and a region of interest.
TEST(LaserLine, ColumnSearchIsTheRowSearchTransposed) {
  auto [on, off] = stripe_pair([](int r) { return 60.0 + 25 * std::sin(0.15 * r); }, 1.6, 120, 3.0, 12);
  // A second stripe in the top rows: double peaks, rejected.
  const cv::Mat second = stripe_pair([](int r) { return 150.0 + 0.2 * r; }, 1.3, 100, 0.0, 13).first;
  cv::Mat top = on.rowRange(0, 20);
  cv::max(top, second.rowRange(0, 20), top);
  for (const cv::Rect region : {cv::Rect(), cv::Rect(20, 5, 170, 50)}) {
    LaserLineOptions rows;
    rows.region = region;
    rows.fit = PeakFit::centre_of_mass;
    const LaserLine by_row = extract_laser_line(on, off, rows);
    cv::Mat on_t, off_t;
    cv::transpose(on, on_t);
    cv::transpose(off, off_t);
    LaserLineOptions columns = rows;
    columns.stripe = StripeDirection::horizontal;
    columns.region = cv::Rect(region.y, region.x, region.height, region.width);
    const LaserLine by_column = extract_laser_line(on_t, off_t, columns);
    ASSERT_GT(by_row.peaks.size(), 20u);
    ASSERT_EQ(by_column.peaks.size(), by_row.peaks.size());
    EXPECT_EQ(by_column.noise_sigma, by_row.noise_sigma);
    EXPECT_EQ(by_column.threshold, by_row.threshold);
    for (std::size_t i = 0; i < by_row.peaks.size(); ++i) {
      EXPECT_EQ(by_column.peaks[i].x, by_row.peaks[i].y);
      EXPECT_EQ(by_column.peaks[i].y, by_row.peaks[i].x);
      EXPECT_EQ(by_column.peaks[i].confidence, by_row.peaks[i].confidence);
    }
  }
  LaserLineOptions outside;
  outside.stripe = StripeDirection::horizontal;
  outside.region = cv::Rect(0, 150, 10, 100);  // rows 150.. of a 64-row frame
  test::expect_error<InvalidInput>([&] { extract_laser_line(on, off, outside); }, {"outside the frame"});
}

TEST(LaserTriangulation, RecoversPointsOfTheLightPlaneThroughADistortedLens) {
  PinholeCamera camera = PinholeCamera::look_at({0, -300, 150}, {0, 0, 40}, Eigen::Vector3d::UnitZ(), 1280, 960, 0.5);
  camera.distortion = {-0.2, 0.08, -0.01, 0.001, -0.0007};
  const LaserPlane plane{turntable_rotation(0.5) * Eigen::Vector3d(0, -300, 40), turntable_rotation(0.5) * Eigen::Vector3d::UnitX()};
  const double angle = 1.1;
  LaserLine line;
  std::vector<Eigen::Vector3d> truth;
  sim::Random random(8);
  while (truth.size() < 200) {
    // A point of the plane, above the platter, in view.
    const Eigen::Vector3d u = plane.normal.cross(Eigen::Vector3d::UnitZ()).normalized();
    const Eigen::Vector3d p = u * random.uniform(-60, 60) + Eigen::Vector3d(0, 0, random.uniform(1, 80));
    const auto pixel = camera.project(p);
    if (!pixel || pixel->x() < 0 || pixel->x() > 1279 || pixel->y() < 0 || pixel->y() > 959) continue;
    line.peaks.push_back({pixel->x(), pixel->y(), 100, 2, 1});
    truth.push_back(turntable_rotation(angle).transpose() * p);
  }
  const cv::Mat grey(960, 1280, CV_8U, cv::Scalar(77));
  LaserScanPoints points;
  triangulate_laser_line(line, camera, plane, angle, grey, points);
  ASSERT_EQ(points.cloud.size(), 200);
  for (Eigen::Index i = 0; i < 200; ++i) {
    EXPECT_LT((points.cloud.positions.row(i).transpose() - truth[static_cast<std::size_t>(i)]).norm(), 1e-6);
    EXPECT_EQ(points.cloud.colors(i, 0), 77);
  }
  EXPECT_EQ(points.confidence.size(), 200u);
}

}  // namespace
}  // namespace scanstation::acquisition

namespace scanstation::acquisition {
namespace {

TEST(OutlierRemoval, StrayPointsGoSurfacePointsStay) {
  sim::Random random(11);
  LaserScanPoints points;
  const Eigen::Index surface = 3000, stray = 30;
  points.cloud.positions.resize(surface + stray, 3);
  points.cloud.colors.resize(surface + stray, 3);
  for (Eigen::Index i = 0; i < surface; ++i) {
    // A dense stripe pattern on a unit-square patch: every point has neighbours.
    points.cloud.positions.row(i) << random.uniform(), (i % 30) / 30.0, 0.001 * random.normal();
    points.confidence.push_back(1.0);
  }
  for (Eigen::Index i = surface; i < surface + stray; ++i) {
    points.cloud.positions.row(i) << random.uniform(-5, 5), random.uniform(-5, 5), random.uniform(1, 5);
    points.confidence.push_back(0.5);
  }
  points.cloud.colors.setConstant(9);
  const Eigen::MatrixX3d before = points.cloud.positions;
  std::vector<Eigen::Index> kept;
  EXPECT_EQ(remove_isolated_points(points, 0.05, 3, &kept), stray);
  EXPECT_EQ(points.cloud.size(), surface);
  // `kept` maps every point left to the row it came from.
  ASSERT_EQ(kept.size(), static_cast<std::size_t>(surface));
  for (Eigen::Index i = 0; i < surface; ++i)
    EXPECT_EQ(points.cloud.positions.row(i), before.row(kept[static_cast<std::size_t>(i)]));
  EXPECT_EQ(points.cloud.colors.rows(), surface);
  EXPECT_EQ(points.confidence.size(), static_cast<std::size_t>(surface));
  EXPECT_LT(points.cloud.positions.col(2).cwiseAbs().maxCoeff(), 0.01);
  EXPECT_EQ(remove_isolated_points(points, 0.05, 3), 0);
  test::expect_error<InvalidInput>([&] { remove_isolated_points(points, 0.0, 3); }, {"radius"});
}

}  // namespace
}  // namespace scanstation::acquisition
