#include "acquisition/stereo_matcher.h"
#include "core/errors.h"
#include "core/image_codecs.h"
#include "test_support.h"

#include <opencv2/imgproc.hpp>

#include <filesystem>

namespace scanstation::acquisition {
namespace {

const std::filesystem::path opencv_data = "/usr/share/doc/opencv-doc/examples/data";

struct Aloe {
  cv::Mat left = image::read((opencv_data / "aloeL.jpg").string(), cv::IMREAD_COLOR);
  cv::Mat right = image::read((opencv_data / "aloeR.jpg").string(), cv::IMREAD_COLOR);
  cv::Mat truth = image::read((opencv_data / "aloeGT.png").string(), cv::IMREAD_GRAYSCALE);
};

// The real Middlebury pair, same disparity range as the reference: the
// default pipeline (left edge padded, left–right check, gap fill, median)
// beats plain SGBM, measured in the same run, by a clear margin; the
// left–right check alone only removes pixels, and those it keeps are better.
TEST(StereoMatcher, BeatsPlainSgbmOnTheMiddleburyAloePair) {
  const Aloe aloe;
  ASSERT_FALSE(aloe.left.empty()) << "opencv-doc is missing: run scripts/setup.sh";
  ASSERT_EQ(aloe.left.size(), aloe.truth.size());
  const cv::Mat plain = compute_disparity(aloe.left, aloe.right, plain_sgbm_options());
  StereoOptions checked = plain_sgbm_options();
  checked.left_right_check = true;
  const cv::Mat consistent = compute_disparity(aloe.left, aloe.right, checked);
  const BadPixelRate reference = bad_pixel_rate(plain, aloe.truth);
  const BadPixelRate improved = bad_pixel_rate(compute_disparity(aloe.left, aloe.right), aloe.truth);
  std::printf("aloe bad >1px / >2px / density: plain SGBM %.1f%% / %.1f%% / %.1f%%, scanstation %.1f%% / %.1f%% / %.1f%%\n",
              100 * reference.above_1px, 100 * reference.above_2px, 100 * reference.density, 100 * improved.above_1px,
              100 * improved.above_2px, 100 * improved.density);
  EXPECT_GT(reference.valid_pixels, 100000);
  EXPECT_LT(improved.above_1px, reference.above_1px - 0.08);
  EXPECT_LT(improved.above_2px, reference.above_2px - 0.10);
  EXPECT_DOUBLE_EQ(improved.density, 1.0);

  EXPECT_EQ(cv::countNonZero((consistent >= 0) & (plain < 0)), 0);
  EXPECT_EQ(cv::norm(consistent, plain, cv::NORM_INF, consistent >= 0), 0.0);
  EXPECT_LT(cv::countNonZero(consistent >= 0), cv::countNonZero(plain >= 0));
  const BadPixelRate kept = bad_pixel_rate(consistent, aloe.truth);
  const auto wrong_among_matched = [](const BadPixelRate& b) { return (b.above_1px - (1 - b.density)) / b.density; };
  EXPECT_LT(wrong_among_matched(kept), wrong_among_matched(reference));
}

// At half resolution (disparities halve too), to keep the suite quick.
TEST(StereoMatcher, WlsFilterGivesADenseMap) {
  const Aloe aloe;
  ASSERT_FALSE(aloe.left.empty());
  cv::Mat left, right, truth;
  cv::pyrDown(aloe.left, left);
  cv::pyrDown(aloe.right, right);
  cv::resize(aloe.truth, truth, left.size(), 0, 0, cv::INTER_NEAREST);
  truth.convertTo(truth, CV_32F, 0.5);
  StereoOptions wls;
  wls.num_disparities = 64;
  wls.post_filter = DisparityPostFilter::wls;
  const BadPixelRate rate = bad_pixel_rate(compute_disparity(left, right, wls), truth);
  std::printf("aloe with WLS: bad >1px %.1f%%, >2px %.1f%%\n", 100 * rate.above_1px, 100 * rate.above_2px);
  EXPECT_DOUBLE_EQ(rate.density, 1.0);
  EXPECT_LT(rate.above_2px, 0.2);
}

TEST(StereoMatcher, RejectsMismatchedImagesAndBadOptions) {
  const cv::Mat a(40, 60, CV_8U, cv::Scalar(0)), b(40, 61, CV_8U, cv::Scalar(0));
  test::expect_error<InvalidInput>([&] { compute_disparity(a, b); }, {"same size"});
  StereoOptions odd;
  odd.num_disparities = 100;
  test::expect_error<InvalidInput>([&] { compute_disparity(a, a, odd); }, {"multiple of 16"});
  const cv::Mat f(40, 60, CV_32F, cv::Scalar(0));
  test::expect_error<InvalidInput>([&] { compute_disparity(f, f); }, {"8-bit"});
  // Beyond 16-bit fixed point OpenCV wrote past its buffers (heap corruption
  // at a smallest disparity of 97123); beyond the width nothing can match.
  StereoOptions far;
  far.min_disparity = 97123;
  test::expect_error<InvalidInput>([&] { compute_disparity(a, a, far); }, {"97123 to 97251", "2048"});
  far.min_disparity = 0;
  far.num_disparities = 4096;
  test::expect_error<InvalidInput>([&] { compute_disparity(a, a, far); }, {"0 to 4096", "2048"});
  far.num_disparities = 16;
  far.min_disparity = 60;
  test::expect_error<InvalidInput>([&] { compute_disparity(a, a, far); }, {"smallest disparity (60", "width (60"});
}

}  // namespace
}  // namespace scanstation::acquisition
