// The processing parameters of a turntable stereo scan, as one object
// recorded in a session's manifest (the stereo counterpart of
// laser_scan_parameters.h).
#pragma once

#include "acquisition/stereo_reconstruction.h"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace scanstation::acquisition {

/// reconstruction  matcher and point filters (stereo_reconstruction.h); its
///                 disparity range and its maximum_radius/maximum_height
///                 are set from the working volume, not from here
/// volume_radius, volume_height  the working volume, a cylinder about the
///                 turntable axis standing on the platter: the disparity
///                 search covers it (fit_disparity_range), points outside it
///                 are background
/// num_disparities  0: the disparity search spans the working volume
///                 (fit_disparity_range); else this many disparities (a
///                 multiple of 16) from the volume's farthest point on:
///                 fewer miss the nearest surfaces, more search nearer than
///                 the volume reaches
/// outlier_radius, outlier_neighbours  radius outlier removal over the whole
///                 cloud after the last step (0 = off), as for the laser
/// min_spacing     least distance between two points of the scan
///                 (point_spacing.h; 0 = every point), as for the laser
struct StereoScanParameters {
  StereoReconstructionOptions reconstruction;
  double volume_radius = 42.0;
  double volume_height = 82.0;
  int num_disparities = 0;
  double outlier_radius = 0.0;
  int outlier_neighbours = 2;
  double min_spacing = 0.0;
};

/// The defaults of a turntable stereo scan: reconstruction_matcher_options()
/// (no invented geometry) and every 8th pixel of every 8th row.
StereoScanParameters stereo_scan_defaults();

/// {"block_size", "uniqueness_ratio", "speckle_window_size", "speckle_range",
///  "left_right_tolerance", "minimum_height", "discontinuity",
///  "minimum_texture", "pixel_step", "cell_mean", "volume_radius", "volume_height",
///  "num_disparities", "outlier_radius", "outlier_neighbours", "min_spacing"}
nlohmann::json to_json(const StereoScanParameters& parameters);

/// Reads what to_json wrote; a key that is absent keeps its value in `base`
/// and is listed in `missing` (when given) — except "num_disparities", "min_spacing" and
/// "cell_mean", which sessions recorded before they existed lack (0: fitted
/// to the volume; 0: every point; false: each pixel alone). A key of the wrong type or out of
/// range throws InvalidInput naming `where` and the key.
StereoScanParameters stereo_scan_parameters_from_json(const nlohmann::json& value, const std::string& where,
                                                      const StereoScanParameters& base = stereo_scan_defaults(),
                                                      std::vector<std::string>* missing = nullptr);

}  // namespace scanstation::acquisition
