// Dense stereo on a rectified pair: OpenCV's semi-global block matching with
// its parameters exposed, a left–right consistency check, and post-filtering.
#pragma once

#include <opencv2/core.hpp>

namespace scanstation::acquisition {

/// What happens to pixels without a trusted disparity after matching.
/// none  left invalid
/// fill  each gap in a row takes the smaller (farther) of the disparities at
///       its two ends: gaps are mostly occlusions, which belong to the background
/// wls   edge-aware weighted-least-squares filtering guided by the left image,
///       weighted by the left–right confidence (opencv_contrib ximgproc), then
///       `fill` for the band at the left edge that the right view never sees
enum class DisparityPostFilter { none, fill, wls };

/// Parameters of cv::StereoSGBM (see its documentation), then ours.
/// p1, p2           smoothness penalties; 0 = 8·c·b² and 32·c·b² (c channels, b block size)
/// speckle_range    disparity variation inside a speckle (OpenCV multiplies it by 16)
/// pad_left_edge    match the left band of num_disparities columns too (see the source)
/// left_right_check  match right-to-left too and invalidate pixels where the two
///                  disparities differ by more than left_right_tolerance pixels
/// median_size      median filter (3 or 5, 0 = none) after the fill, against streaks
struct StereoOptions {
  int min_disparity = 0;
  int num_disparities = 128;  // multiple of 16
  int block_size = 5;
  int p1 = 0, p2 = 0;
  int disp12_max_diff = 1;
  int pre_filter_cap = 63;
  int uniqueness_ratio = 10;
  int speckle_window_size = 100;
  int speckle_range = 2;
  int mode = 3;  // cv::StereoSGBM::MODE_SGBM_3WAY
  bool pad_left_edge = true;
  bool left_right_check = true;
  double left_right_tolerance = 1.0;
  DisparityPostFilter post_filter = DisparityPostFilter::fill;
  int median_size = 5;
  double wls_lambda = 8000.0, wls_sigma = 1.5;
};

/// The plain matcher of OpenCV's stereo_match sample: block 5, 128 disparities,
/// 3-way, speckle range 32, no padding, no left–right check, no post-filter.
/// The reference to beat.
StereoOptions plain_sgbm_options();

/// left, right  rectified 8-bit images (grey or BGR) of the same size
/// Returns CV_32F disparities in pixels (left x − right x); invalid pixels are
/// negative. Throws InvalidInput for mismatched or non-8-bit images or bad options.
cv::Mat compute_disparity(const cv::Mat& left, const cv::Mat& right, const StereoOptions& options = {});

/// Middlebury-style error of a disparity map against ground truth.
/// above_1px, above_2px  fractions of valid ground-truth pixels whose error
///                       exceeds 1 / 2 px; a pixel without disparity counts as bad
/// density               fraction of valid ground-truth pixels with a disparity
struct BadPixelRate {
  double above_1px = 0, above_2px = 0, density = 0;
  long valid_pixels = 0;
};

/// ground_truth  disparities in pixels (any single-channel type), 0 = unknown
BadPixelRate bad_pixel_rate(const cv::Mat& disparity, const cv::Mat& ground_truth);

}  // namespace scanstation::acquisition
