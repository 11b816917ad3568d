// The processing parameters of a turntable laser scan, as one object recorded
// in a session's manifest and overridable at replay.
#pragma once

#include "acquisition/laser_line.h"
#include "acquisition/laser_triangulation.h"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace scanstation::acquisition {

/// line            stripe extraction (laser_line.h)
/// triangulation   ray–plane cut and platter/background rejection (laser_triangulation.h)
/// outlier_radius  radius outlier removal over the whole cloud (outlier_removal.h),
///                 in station units; 0 = off
/// outlier_neighbours  neighbours a point needs within outlier_radius
/// min_spacing     least distance between two points of the scan (SpacingFilter,
///                 point_spacing.h), in station units; 0 = every point
/// row_step        keep the stripe centres of every n-th row (column for a
///                 horizontal stripe): the spacing along the stripe matched to
///                 the spacing between turntable steps, so that the points are
///                 spread evenly enough for constriction (thesis §5.5: the
///                 boundary is only as good as the sampling is dense and even)
struct LaserScanParameters {
  LaserLineOptions line;
  LaserTriangulationOptions triangulation;
  double outlier_radius = 0.0;
  int outlier_neighbours = 2;
  double min_spacing = 0.0;
  int row_step = 1;
};

/// {"peak_fit": "gaussian"|"centre_of_mass"|"parabolic", "threshold_sigmas",
///  "minimum_contrast", "minimum_width", "maximum_width", "saturation",
///  "double_peak_ratio", "region": [x, y, w, h], "minimum_height",
///  "maximum_radius" (null = none), "minimum_incidence", "outlier_radius",
///  "outlier_neighbours", "min_spacing", "row_step"}
nlohmann::json to_json(const LaserScanParameters& parameters);

/// Reads what to_json wrote; a key that is absent keeps its value in `base`
/// and is listed in `missing` (when given) — except "min_spacing", which
/// sessions recorded before it existed lack (0: every point). A key of the wrong type or out of
/// range throws InvalidInput naming `where` and the key.
LaserScanParameters laser_scan_parameters_from_json(const nlohmann::json& value, const std::string& where,
                                                    const LaserScanParameters& base = {},
                                                    std::vector<std::string>* missing = nullptr);

/// "gaussian", "centre_of_mass", "parabolic" and back (InvalidInput otherwise).
std::string peak_fit_name(PeakFit fit);
PeakFit parse_peak_fit(const std::string& name);

}  // namespace scanstation::acquisition
