#include "acquisition/stereo_matcher.h"

#include "acquisition/ximgproc_module.h"
#include "core/errors.h"
#include "core/loadable_module.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace scanstation::acquisition {

namespace {

constexpr float invalid = -1.0f;
constexpr int kMaxDisparity = 2048;

const XimgprocTable& ximgproc() {
  static const XimgprocTable& table = module_table<XimgprocTable>("ximgproc", ximgproc_table_entry);
  return table;
}

cv::Ptr<cv::StereoSGBM> make_matcher(const StereoOptions& o, int channels) {
  if (o.num_disparities <= 0 || o.num_disparities % 16 != 0)
    throw InvalidInput("stereo: the number of disparities must be a positive multiple of 16");
  if (o.block_size < 1 || o.block_size % 2 == 0) throw InvalidInput("stereo: the block size must be odd and positive");
  if (o.median_size != 0 && o.median_size != 3 && o.median_size != 5)
    throw InvalidInput("stereo: the median size must be 0 (none), 3 or 5");
  const int area = channels * o.block_size * o.block_size;
  return cv::StereoSGBM::create(o.min_disparity, o.num_disparities, o.block_size, o.p1 > 0 ? o.p1 : 8 * area,
                                o.p2 > 0 ? o.p2 : 32 * area, o.disp12_max_diff, o.pre_filter_cap, o.uniqueness_ratio,
                                o.speckle_window_size, o.speckle_range, o.mode);
}

// CV_16S fixed point (×16) → CV_32F pixels, invalid (below min_disparity) → −1.
cv::Mat to_pixels(const cv::Mat& fixed, int min_disparity) {
  cv::Mat pixels;
  fixed.convertTo(pixels, CV_32F, 1.0 / 16.0);
  pixels.setTo(invalid, pixels < static_cast<float>(min_disparity));
  return pixels;
}

// Invalidates left disparities that the right view does not confirm.
void left_right_check(cv::Mat& left, const cv::Mat& right, double tolerance) {
  for (int r = 0; r < left.rows; ++r) {
    float* l = left.ptr<float>(r);
    const float* rr = right.ptr<float>(r);
    for (int c = 0; c < left.cols; ++c) {
      if (l[c] < 0) continue;
      const int x = static_cast<int>(std::lround(c - l[c]));
      if (x < 0 || x >= left.cols || rr[x] < 0 || std::abs(rr[x] - l[c]) > tolerance) l[c] = invalid;
    }
  }
}

void fill_gaps(cv::Mat& disparity) {
  for (int r = 0; r < disparity.rows; ++r) {
    float* d = disparity.ptr<float>(r);
    int c = 0;
    while (c < disparity.cols) {
      if (d[c] >= 0) {
        ++c;
        continue;
      }
      const int start = c;
      while (c < disparity.cols && d[c] < 0) ++c;
      const float left = start > 0 ? d[start - 1] : invalid, right = c < disparity.cols ? d[c] : invalid;
      const float value = left < 0 ? right : right < 0 ? left : std::min(left, right);
      std::fill(d + start, d + c, value);
    }
  }
}

}  // namespace

StereoOptions plain_sgbm_options() {
  StereoOptions o;
  o.speckle_range = 32;
  o.pad_left_edge = false;
  o.left_right_check = false;
  o.post_filter = DisparityPostFilter::none;
  o.median_size = 0;
  return o;
}

cv::Mat compute_disparity(const cv::Mat& left, const cv::Mat& right, const StereoOptions& options) {
  if (left.empty() || left.size() != right.size() || left.type() != right.type())
    throw InvalidInput("stereo: the left and right images must be non-empty and of the same size and type");
  if (left.depth() != CV_8U || (left.channels() != 1 && left.channels() != 3))
    throw InvalidInput("stereo: the images must be 8-bit grey or BGR");
  // SGBM keeps disparities as 16-bit fixed point (×16): a search reaching
  // 2048 pixels overflows them, and OpenCV then writes past its buffers.
  const long reach = static_cast<long>(options.min_disparity) + options.num_disparities;
  if (options.min_disparity < -kMaxDisparity || reach > kMaxDisparity)
    throw InvalidInput("stereo: the disparities searched, " + std::to_string(options.min_disparity) + " to " +
                       std::to_string(reach) + " pixels, must lie within ±" + std::to_string(kMaxDisparity) +
                       " (OpenCV keeps them as 16-bit fixed point)");
  if (options.min_disparity >= left.cols)
    throw InvalidInput("stereo: the smallest disparity (" + std::to_string(options.min_disparity) +
                       " pixels) must be less than the image width (" + std::to_string(left.cols) +
                       " pixels): no pixel could match");
  const cv::Ptr<cv::StereoSGBM> matcher = make_matcher(options, left.channels());
  cv::Mat left_fixed;
  if (options.pad_left_edge) {
    // SGBM leaves the first num_disparities columns empty, as if every pixel
    // there could have the largest disparity. Widen both images on the left
    // so those pixels are matched against the disparities they can have.
    const int pad = std::max(0, options.min_disparity + options.num_disparities);  // none when every disparity is negative
    cv::Mat wide_left, wide_right;
    cv::copyMakeBorder(left, wide_left, 0, 0, pad, 0, cv::BORDER_REPLICATE);
    cv::copyMakeBorder(right, wide_right, 0, 0, pad, 0, cv::BORDER_REPLICATE);
    matcher->compute(wide_left, wide_right, left_fixed);
    left_fixed = left_fixed.colRange(pad, left_fixed.cols).clone();
  } else {
    matcher->compute(left, right, left_fixed);
  }
  if (options.post_filter == DisparityPostFilter::wls) {
    // The filter runs its own left–right confidence from the right matcher.
    const cv::Ptr<cv::StereoMatcher> right_matcher = ximgproc().right_matcher(matcher);
    cv::Mat right_fixed, filtered;
    right_matcher->compute(right, left, right_fixed);
    const cv::Ptr<cv::ximgproc::DisparityWLSFilter> wls = ximgproc().wls_filter(matcher);
    wls->setLambda(options.wls_lambda);
    wls->setSigmaColor(options.wls_sigma);
    wls->setLRCthresh(static_cast<int>(std::lround(options.left_right_tolerance * 16)));
    wls->filter(left_fixed, left, filtered, right_fixed);
    // The filter leaves the left band where the right view cannot match (the
    // first num_disparities columns) empty: fill it like any other gap.
    cv::Mat disparity = to_pixels(filtered, options.min_disparity);
    fill_gaps(disparity);
    return disparity;
  }
  cv::Mat disparity = to_pixels(left_fixed, options.min_disparity);
  if (options.left_right_check) {
    const cv::Ptr<cv::StereoMatcher> right_matcher = ximgproc().right_matcher(matcher);
    cv::Mat right_fixed;
    right_matcher->compute(right, left, right_fixed);
    // The right matcher reports negated disparities.
    cv::Mat right_pixels;
    right_fixed.convertTo(right_pixels, CV_32F, -1.0 / 16.0);
    right_pixels.setTo(invalid, right_pixels < static_cast<float>(options.min_disparity));
    left_right_check(disparity, right_pixels, options.left_right_tolerance);
  }
  if (options.post_filter == DisparityPostFilter::fill) fill_gaps(disparity);
  if (options.median_size > 0) cv::medianBlur(disparity, disparity, options.median_size);
  return disparity;
}

BadPixelRate bad_pixel_rate(const cv::Mat& disparity, const cv::Mat& ground_truth) {
  if (disparity.size() != ground_truth.size() || disparity.type() != CV_32F || ground_truth.channels() != 1)
    throw InvalidInput("stereo: disparity (CV_32F) and ground truth (one channel) must have the same size");
  cv::Mat truth;
  ground_truth.convertTo(truth, CV_32F);
  BadPixelRate rate;
  long bad1 = 0, bad2 = 0, dense = 0;
  for (int r = 0; r < truth.rows; ++r)
    for (int c = 0; c < truth.cols; ++c) {
      const float t = truth.at<float>(r, c), d = disparity.at<float>(r, c);
      if (t <= 0) continue;
      ++rate.valid_pixels;
      const double error = d >= 0 ? std::abs(d - t) : std::numeric_limits<double>::infinity();
      dense += d >= 0;
      bad1 += error > 1.0;
      bad2 += error > 2.0;
    }
  if (rate.valid_pixels > 0) {
    const double n = static_cast<double>(rate.valid_pixels);
    rate.above_1px = bad1 / n;
    rate.above_2px = bad2 / n;
    rate.density = dense / n;
  }
  return rate;
}

}  // namespace scanstation::acquisition
