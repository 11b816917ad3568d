#include "acquisition/stereo_calibration.h"
#include "core/errors.h"
#include "core/image_codecs.h"
#include "test_support.h"

#include <opencv2/calib3d.hpp>

#include <cstdio>
#include <filesystem>

namespace scanstation::acquisition {
namespace {

// OpenCV's sample chessboard pairs (left01…left14, number 10 absent), 9×6 inner corners.
std::pair<std::vector<cv::Mat>, std::vector<cv::Mat>> opencv_chessboards() {
  const std::filesystem::path data = "/usr/share/doc/opencv-doc/examples/data";
  std::vector<cv::Mat> left, right;
  for (int i = 1; i <= 14; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%02d.jpg", i);
    const std::filesystem::path l_path = data / ("left" + std::string(name)), r_path = data / ("right" + std::string(name));
    if (!std::filesystem::exists(l_path) || !std::filesystem::exists(r_path)) continue;
    const cv::Mat l = image::read(l_path.string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat r = image::read(r_path.string(), cv::IMREAD_GRAYSCALE);
    left.push_back(l);
    right.push_back(r);
  }
  return {left, right};
}

TEST(StereoCalibration, RealChessboardPairsAgainstOpenCvSampleFlags) {
  const auto [left, right] = opencv_chessboards();
  ASSERT_EQ(left.size(), 13u) << "opencv-doc is missing: run scripts/setup.sh";
  const StereoCalibration ours = calibrate_stereo(left, right, {9, 6}, 1.0);
  const StereoCalibration sample = calibrate_stereo(left, right, {9, 6}, 1.0, StereoModel::opencv_sample);
  std::printf("stereo RMS: %.3f px (left %.3f, right %.3f) over %zu pairs; OpenCV stereo_calib flags %.3f px\n", ours.rms,
              ours.left.rms, ours.right.rms, ours.used_views.size(), sample.rms);
  for (std::size_t v = 0; v < ours.per_view_rms.size(); ++v)
    std::printf("  pair %zu: %.3f / %.3f px\n", ours.used_views[v] + 1, ours.per_view_rms[v][0], ours.per_view_rms[v][1]);
  EXPECT_GE(ours.used_views.size(), 10u);
  EXPECT_EQ(ours.per_view_rms.size(), ours.used_views.size());
  EXPECT_EQ(ours.left.per_view_rms.size(), ours.used_views.size());
  EXPECT_LT(ours.rms, 1.0);
  EXPECT_LT(ours.rms, 1.2 * sample.rms);
  // A horizontal rig about 3.3 squares apart, as the sample images show.
  EXPECT_LT(ours.translation[0], -2.0);
  EXPECT_LT(std::abs(ours.translation[1]), 0.5);

  // Rectified, the corners of a pair lie on the same row (the sample's
  // "average epipolar error", here after rectification).
  const cv::Mat K1(ours.left.camera_matrix), K2(ours.right.camera_matrix);
  double mismatch = 0;
  std::size_t corners = 0;
  for (const std::size_t v : ours.used_views) {
    const auto l = find_chessboard(left[v], {9, 6});
    const auto r = find_chessboard(right[v], {9, 6});
    ASSERT_TRUE(l && r);
    std::vector<cv::Point2f> lr, rr;
    cv::undistortPoints(*l, lr, K1, ours.left.distortion, ours.r1, ours.p1);
    cv::undistortPoints(*r, rr, K2, ours.right.distortion, ours.r2, ours.p2);
    for (std::size_t k = 0; k < lr.size(); ++k) mismatch += std::abs(lr[k].y - rr[k].y);
    corners += lr.size();
  }
  std::printf("rectified row mismatch: %.3f px on average\n", mismatch / static_cast<double>(corners));
  EXPECT_LT(mismatch / static_cast<double>(corners), 0.3);
}

TEST(StereoCalibration, TooFewBoardsIsAClearError) {
  const auto [left, right] = opencv_chessboards();
  ASSERT_FALSE(left.empty());
  const std::vector<cv::Mat> two_left(left.begin(), left.begin() + 2), two_right(right.begin(), right.begin() + 2);
  test::expect_error<InvalidInput>([&] { calibrate_stereo(two_left, two_right, {9, 6}, 1.0); }, {"only 2 pairs", "9x6"});
  test::expect_error<InvalidInput>([&] { calibrate_stereo(left, two_right, {9, 6}, 1.0); }, {"left but"});
}

}  // namespace
}  // namespace scanstation::acquisition
