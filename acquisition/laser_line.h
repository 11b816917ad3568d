// Laser-line extraction: the sub-pixel centre of the laser stripe in every
// image row (or every column, for a horizontal stripe), from a laser-on /
// laser-off frame pair.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace scanstation::acquisition {

/// How the sub-pixel centre of a peak is found.
/// centre_of_mass  intensity-weighted mean over the peak (robust, biased by asymmetric tails)
/// gaussian        three-point Gaussian fit on the logarithms (exact for a Gaussian beam)
/// parabolic       three-point parabola (fast, biased towards the nearest pixel)
enum class PeakFit { centre_of_mass, gaussian, parabolic };

/// Which way the stripe runs in the image, and so which lines are searched.
/// vertical    along the columns (a vertical light plane seen from beside it):
///             one peak per row
/// horizontal  along the rows (a horizontal light plane seen from above or
///             below): one peak per column
enum class StripeDirection { vertical, horizontal };

/// stripe              the stripe's direction
/// fit                 sub-pixel estimator
/// threshold_sigmas    a peak must rise this many noise σ above zero; σ of the
///                     difference image is estimated from the frames as a
///                     function of the laser-off level (shot noise grows with it)
/// minimum_contrast    floor of the threshold in grey levels, for noise-free frames
/// minimum_width       peaks narrower than this at half maximum are single-pixel
///                     noise spikes, not a focused stripe (which spreads over ≥ 2 px)
/// maximum_width       peaks wider than this at half maximum (pixels) are rejected:
///                     grazing surfaces, stripe edges, interreflections
/// saturation          a peak whose laser-on pixels reach this level is rejected
///                     (its top is clipped, the centre is not measurable)
/// double_peak_ratio   a second peak (away from the first) of at least this
///                     fraction of the first makes the row ambiguous: rejected
/// region              rows and columns searched; an empty rectangle = the whole frame
struct LaserLineOptions {
  StripeDirection stripe = StripeDirection::vertical;
  PeakFit fit = PeakFit::gaussian;
  double threshold_sigmas = 6.0;
  double minimum_contrast = 10.0;
  int minimum_width = 2;
  int maximum_width = 10;
  int saturation = 255;
  double double_peak_ratio = 0.5;
  cv::Rect region;
};

/// One stripe centre: image position (x sub-pixel and y the row, or for a
/// horizontal stripe x the column and y sub-pixel), peak height
/// over the laser-off frame (grey levels), width at half maximum (pixels) and
/// a confidence in (0, 1] from the contrast over the threshold and the width.
struct LinePeak {
  double x = 0, y = 0;
  float contrast = 0, width = 0, confidence = 0;
};

/// The peaks found, at most one per row (column), in row (column) order, with
/// the noise σ of the difference image and the threshold at the brightest
/// laser-off level.
struct LaserLine {
  std::vector<LinePeak> peaks;
  double noise_sigma = 0, threshold = 0;
};

/// laser_on, laser_off  8-bit single-channel frames of the same size
/// Throws InvalidInput for frames of another type or different sizes, or a
/// region outside the frame. Each row (or column, options.stripe) is
/// searched once; the column search is the row search on the transposed
/// frames, so both have the same sub-pixel accuracy and rejections.
LaserLine extract_laser_line(const cv::Mat& laser_on, const cv::Mat& laser_off, const LaserLineOptions& options = {});

}  // namespace scanstation::acquisition
