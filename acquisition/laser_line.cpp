#include "acquisition/laser_line.h"

#include "core/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

namespace scanstation::acquisition {

namespace {

// Noise σ of the signed difference on − off as a function of the laser-off
// level: shot noise grows with the signal, so one global σ would be too low
// on bright surfaces (false peaks) or too high on dark ones (lost stripe).
// Per band of 16 levels, σ = 1.4826 · median |on − off| over every 8th row —
// the stripe covers a few pixels per row, so the median sees background
// only. The 8-bit values are binned, so the median is interpolated inside its
// bin (value k covers [k − ½, k + ½]). σ is made non-decreasing in the level;
// bands without enough samples take the σ of the band below.
std::array<double, 256> difference_noise_sigma(const cv::Mat& on, const cv::Mat& off, const cv::Rect& region) {
  constexpr int bands = 16;
  std::vector<std::array<std::uint32_t, 256>> histogram(bands, std::array<std::uint32_t, 256>{});
  std::array<std::uint64_t, bands> count{};
  for (int r = region.y; r < region.y + region.height; r += 8) {
    const std::uint8_t* a = on.ptr<std::uint8_t>(r);
    const std::uint8_t* b = off.ptr<std::uint8_t>(r);
    for (int c = region.x; c < region.x + region.width; ++c) {
      ++histogram[static_cast<std::size_t>(b[c] / 16)][static_cast<std::size_t>(std::abs(a[c] - b[c]))];
      ++count[static_cast<std::size_t>(b[c] / 16)];
    }
  }
  std::array<double, bands> sigma{};
  double previous = 0;
  for (std::size_t band = 0; band < bands; ++band) {
    sigma[band] = previous;
    if (count[band] < 64) continue;
    const double half = 0.5 * static_cast<double>(count[band]);
    double below = 0;
    for (std::size_t k = 0; k < 256; ++k) {
      const double in_bin = histogram[band][k];
      if (below + in_bin >= half) {
        const double lo = k == 0 ? 0.0 : k - 0.5, hi = k + 0.5;
        sigma[band] = std::max(previous, 1.4826 * (lo + (hi - lo) * (half - below) / std::max(in_bin, 1.0)));
        break;
      }
      below += in_bin;
    }
    previous = sigma[band];
  }
  std::array<double, 256> by_level{};
  for (std::size_t level = 0; level < 256; ++level) by_level[level] = sigma[level / 16];
  return by_level;
}

// Sub-pixel offset of the peak from its brightest pixel.
double three_point_offset(PeakFit fit, double left, double centre, double right) {
  if (fit == PeakFit::gaussian) {
    if (left <= 0 || right <= 0) fit = PeakFit::parabolic;  // log undefined: fall back
    else {
      left = std::log(left), centre = std::log(centre), right = std::log(right);
    }
  }
  const double curvature = left - 2.0 * centre + right;
  if (!(curvature < 0)) return 0.0;
  return std::clamp(0.5 * (left - right) / curvature, -0.5, 0.5);
}

}  // namespace

LaserLine extract_laser_line(const cv::Mat& laser_on, const cv::Mat& laser_off, const LaserLineOptions& options) {
  if (laser_on.type() != CV_8UC1 || laser_off.type() != CV_8UC1)
    throw InvalidInput("laser line: the laser-on and laser-off frames must be 8-bit single-channel images");
  if (laser_on.size() != laser_off.size())
    throw InvalidInput("laser line: the laser-on and laser-off frames differ in size");
  if (options.stripe == StripeDirection::horizontal) {
    // Columns become rows: one search serves both directions. The transpose
    // costs two passes over the frames, small against the search itself.
    cv::Mat on, off;
    cv::transpose(laser_on, on);
    cv::transpose(laser_off, off);
    LaserLineOptions transposed = options;
    transposed.stripe = StripeDirection::vertical;
    transposed.region = cv::Rect(options.region.y, options.region.x, options.region.height, options.region.width);
    LaserLine line = extract_laser_line(on, off, transposed);
    for (LinePeak& peak : line.peaks) std::swap(peak.x, peak.y);
    return line;
  }
  const cv::Rect frame(0, 0, laser_on.cols, laser_on.rows);
  const cv::Rect region = options.region.empty() ? frame : options.region;
  if ((region & frame) != region)
    throw InvalidInput("laser line: the region of interest reaches outside the frame");

  LaserLine line;
  const std::array<double, 256> noise = difference_noise_sigma(laser_on, laser_off, region);
  std::array<int, 256> threshold_at{};  // by laser-off level
  for (std::size_t level = 0; level < 256; ++level)
    threshold_at[level] = static_cast<int>(std::ceil(std::max(options.minimum_contrast, options.threshold_sigmas * noise[level])));
  line.noise_sigma = noise.back();
  line.threshold = threshold_at.back();
  const int lowest_threshold = *std::min_element(threshold_at.begin(), threshold_at.end());

  std::vector<std::uint8_t> difference(static_cast<std::size_t>(region.width));
  std::uint8_t* d = difference.data();
  const int n = region.width;
  for (int r = region.y; r < region.y + region.height; ++r) {
    const std::uint8_t* on = laser_on.ptr<std::uint8_t>(r) + region.x;
    const std::uint8_t* off = laser_off.ptr<std::uint8_t>(r) + region.x;
    // Saturating on − off and its maximum: two plain loops the compiler vectorises.
    for (int c = 0; c < n; ++c) d[c] = static_cast<std::uint8_t>(std::max(on[c] - off[c], 0));
    int best = 0;
    for (int c = 0; c < n; ++c) best = std::max(best, static_cast<int>(d[c]));
    if (best < lowest_threshold) continue;
    const int peak = static_cast<int>(std::find(d, d + n, best) - d);
    const int threshold = threshold_at[off[peak]];
    if (best < threshold) continue;

    // The run above half maximum around the peak gives the width.
    const int half = (best + 1) / 2;
    int a = peak, b = peak;
    while (a > 0 && d[a - 1] >= half) --a;
    while (b + 1 < n && d[b + 1] >= half) ++b;
    const int width = b - a + 1;
    if (width < options.minimum_width || width > options.maximum_width) continue;
    if (*std::max_element(on + a, on + b + 1) >= options.saturation) continue;

    // Anything comparable outside the peak's neighbourhood: two stripes
    // (a reflection, a second laser) and no way to tell which is right.
    const int guard = width + 2;
    int second = 0;
    for (int c = 0; c < std::max(a - guard, 0); ++c) second = std::max(second, static_cast<int>(d[c]));
    for (int c = std::min(b + guard + 1, n); c < n; ++c) second = std::max(second, static_cast<int>(d[c]));
    if (second >= threshold && second >= options.double_peak_ratio * best) continue;

    double x = peak;
    if (options.fit == PeakFit::centre_of_mass) {
      // Over about ±3σ of a Gaussian stripe: a window cut at the half
      // maximum would pull the centre towards the brightest pixel.
      const int margin = width / 2 + 1;
      double sum = 0, moment = 0;
      for (int c = std::max(a - margin, 0); c <= std::min(b + margin, n - 1); ++c) {
        sum += d[c];
        moment += static_cast<double>(d[c]) * c;
      }
      x = moment / sum;
    } else if (peak > 0 && peak + 1 < n) {
      x = peak + three_point_offset(options.fit, d[peak - 1], best, d[peak + 1]);
    }
    LinePeak found;
    found.x = x + region.x;
    found.y = r;
    found.contrast = static_cast<float>(best);
    found.width = static_cast<float>(width);
    // Contrast well over the threshold and a narrow stripe are trustworthy.
    found.confidence = static_cast<float>((1.0 - std::exp(-best / (2.0 * threshold))) *
                                          std::min(1.0, 4.0 / width));
    line.peaks.push_back(found);
  }
  return line;
}

}  // namespace scanstation::acquisition
