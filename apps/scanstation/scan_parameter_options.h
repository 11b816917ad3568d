// The processing options `scan` and `replay` share, of the laser rig and of
// the stereo rig: each given option overrides the base parameters (the
// defaults for a scan, the session's recorded ones for a replay).
#pragma once

#include "acquisition/laser_scan_parameters.h"
#include "acquisition/stereo_scan_parameters.h"

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace scanstation::app {

struct ScanParameterOptions {
  std::optional<std::string> peak_fit;
  std::optional<double> threshold_sigmas, minimum_contrast, double_peak_ratio, minimum_height, maximum_radius,
      outlier_radius;
  std::optional<int> minimum_width, maximum_width, outlier_neighbours, row_step;

  void add_to(CLI::App& cli);
  bool any() const;
  acquisition::LaserScanParameters apply(acquisition::LaserScanParameters base) const;
};

struct StereoParameterOptions {
  std::optional<int> block_size, num_disparities, uniqueness_ratio, pixel_step;
  bool cell_mean = false;  // a flag: on when given

  void add_to(CLI::App& cli);
  /// The first option given ("--block-size", ...), or "" when none was.
  std::string given() const;
  acquisition::StereoScanParameters apply(acquisition::StereoScanParameters base) const;
};

/// 0 (every point) or a least point spacing from 1e-6 to 1e9 (mm).
CLI::Validator least_spacing();

/// --min-spacing, which either rig takes (point_spacing.h).
struct SpacingOption {
  std::optional<double> min_spacing;

  void add_to(CLI::App& cli);
  /// `p` with the spacing given, as it was when none was.
  template <typename Parameters>
  Parameters apply(Parameters p) const {
    if (min_spacing) p.min_spacing = *min_spacing;
    return p;
  }
};

}  // namespace scanstation::app
