#include "scan_parameter_options.h"

namespace scanstation::app {

void ScanParameterOptions::add_to(CLI::App& cli) {
  cli.add_option("--peak-fit", peak_fit, "Sub-pixel stripe centre: gaussian, centre_of_mass or parabolic")
      ->check(CLI::IsMember({"gaussian", "centre_of_mass", "parabolic"}));
  cli.add_option("--threshold-sigmas", threshold_sigmas, "A stripe peak must rise this many noise sigmas")
      ->check(CLI::NonNegativeNumber);
  cli.add_option("--min-contrast", minimum_contrast, "Floor of the peak threshold (grey levels)")
      ->check(CLI::NonNegativeNumber);
  cli.add_option("--min-width", minimum_width, "Narrowest stripe peak kept (pixels at half maximum)")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--max-width", maximum_width, "Widest stripe peak kept (pixels at half maximum)")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--double-peak-ratio", double_peak_ratio, "A second peak this strong makes a row ambiguous")
      ->check(CLI::PositiveNumber);
  cli.add_option("--min-height", minimum_height, "Points at or below this height are the platter (mm)");
  cli.add_option("--max-radius", maximum_radius, "Points farther from the axis are background (mm)")
      ->check(CLI::PositiveNumber);
  cli.add_option("--outlier-radius", outlier_radius, "Radius outlier removal (mm; 0 = off)")
      ->check(CLI::NonNegativeNumber);
  cli.add_option("--outlier-neighbours", outlier_neighbours, "Neighbours a point needs within --outlier-radius")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--row-step", row_step,
                 "Keep the stripe centre of every n-th image row: the spacing along the stripe near the spacing "
                 "between steps, for an even sampling")
      ->check(CLI::Range(1, 1000));
}

bool ScanParameterOptions::any() const {
  return peak_fit || threshold_sigmas || minimum_contrast || double_peak_ratio || minimum_height || maximum_radius ||
         outlier_radius || minimum_width || maximum_width || outlier_neighbours || row_step;
}

acquisition::LaserScanParameters ScanParameterOptions::apply(acquisition::LaserScanParameters p) const {
  if (peak_fit) p.line.fit = acquisition::parse_peak_fit(*peak_fit);
  if (threshold_sigmas) p.line.threshold_sigmas = *threshold_sigmas;
  if (minimum_contrast) p.line.minimum_contrast = *minimum_contrast;
  if (minimum_width) p.line.minimum_width = *minimum_width;
  if (maximum_width) p.line.maximum_width = *maximum_width;
  if (double_peak_ratio) p.line.double_peak_ratio = *double_peak_ratio;
  if (minimum_height) p.triangulation.minimum_height = *minimum_height;
  if (maximum_radius) p.triangulation.maximum_radius = *maximum_radius;
  if (outlier_radius) p.outlier_radius = *outlier_radius;
  if (outlier_neighbours) p.outlier_neighbours = *outlier_neighbours;
  if (row_step) p.row_step = *row_step;
  return p;
}

}  // namespace scanstation::app
