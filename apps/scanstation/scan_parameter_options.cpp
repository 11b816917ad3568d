#include "scan_parameter_options.h"

#include "acquisition/json_key.h"
#include "command.h"
#include "core/errors.h"

namespace scanstation::app {

void ScanParameterOptions::add_to(CLI::App& cli) {
  cli.add_option("--peak-fit", peak_fit, "Sub-pixel stripe centre: gaussian, centre_of_mass or parabolic")
      ->check(CLI::IsMember({"gaussian", "centre_of_mass", "parabolic"}));
  cli.add_option("--threshold-sigmas", threshold_sigmas, "A stripe peak must rise this many noise sigmas")
      ->check(finite_range(0.0, 1e6));
  cli.add_option("--min-contrast", minimum_contrast, "Floor of the peak threshold (grey levels)")
      ->check(finite_range(0.0, 65535.0));
  cli.add_option("--min-width", minimum_width, "Narrowest stripe peak kept (pixels at half maximum)")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--max-width", maximum_width, "Widest stripe peak kept (pixels at half maximum)")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--double-peak-ratio", double_peak_ratio, "A second peak this strong makes a row ambiguous")
      ->check(finite_range(1e-9, 1e9));
  cli.add_option("--min-height", minimum_height, "Points at or below this height are the platter (mm)")
      ->check(finite_range(-1e9, 1e9));
  cli.add_option("--max-radius", maximum_radius, "Points farther from the axis are background (mm)")
      ->check(finite_range(1e-9, 1e9));
  cli.add_option("--outlier-radius", outlier_radius, "Radius outlier removal (mm; 0 = off)")
      ->check(finite_range(0.0, 1e9));
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
  if (p.line.minimum_width > p.line.maximum_width)
    throw InvalidInput("the narrowest stripe peak kept (--min-width, " + std::to_string(p.line.minimum_width) +
                       ") is wider than the widest (--max-width, " + std::to_string(p.line.maximum_width) +
                       "): no stripe could be kept");
  return p;
}

CLI::Validator least_spacing() {
  return CLI::Validator(
      [](const std::string& value) {
        const std::optional<double> x = parse_whole<double>(value);
        if (!x || !acquisition::valid_min_spacing(*x))
          return std::string("expected ") + acquisition::kMinSpacingRange + " (mm), got " + value;
        return std::string();
      },
      "0 or 1e-6..1e9");
}

void SpacingOption::add_to(CLI::App& cli) {
  cli.add_option("--min-spacing", min_spacing,
                 "Least distance between two points (mm; 0 = every point): a point nearer one kept before is "
                 "dropped as it arrives, where profiles or views crowd (near the top of an object, between "
                 "overlapping stereo views) and the noise is as large as their spacing")
      ->check(least_spacing());
}

namespace {

// An integer in low..high that is a multiple of `factor`.
CLI::Validator multiple_in(int low, int high, int factor, int offset, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const std::optional<int> v = parse_whole<int>(text);
        if (!v || *v < low || *v > high || (*v - offset) % factor != 0) return "expected " + what + ", got " + text;
        return "";
      },
      what);
}

}  // namespace

void StereoParameterOptions::add_to(CLI::App& cli) {
  cli.add_option("--block-size", block_size, "--rig stereo: SGBM matching block (odd pixels)")
      ->check(multiple_in(1, 51, 2, 1, "an odd integer in 1..51"));
  cli.add_option("--num-disparities", num_disparities,
                 "--rig stereo: disparities searched (a multiple of 16; default: fitted to the working volume)")
      ->check(multiple_in(16, 1024, 16, 0, "a multiple of 16 in 16..1024"));
  cli.add_option("--uniqueness", uniqueness_ratio, "--rig stereo: SGBM uniqueness ratio (percent)")
      ->check(CLI::Range(0, 100));
  cli.add_option("--pixel-step", pixel_step,
                 "--rig stereo: reproject every n-th pixel of every n-th row (an even sampling, sparse enough for the "
                 "live boundary; default 8)")
      ->check(CLI::Range(1, 1000));
  cli.add_flag("--cell-mean", cell_mean,
                 "--rig stereo: each point from the mean of the matched pixels of its pixel-step cell on the same "
                 "surface, not from its pixel alone (less matching noise; off by default)");
}

std::string StereoParameterOptions::given() const {
  if (block_size) return "--block-size";
  if (num_disparities) return "--num-disparities";
  if (uniqueness_ratio) return "--uniqueness";
  if (pixel_step) return "--pixel-step";
  if (cell_mean) return "--cell-mean";
  return "";
}

acquisition::StereoScanParameters StereoParameterOptions::apply(acquisition::StereoScanParameters p) const {
  if (block_size) p.reconstruction.matcher.block_size = *block_size;
  if (num_disparities) p.num_disparities = *num_disparities;
  if (uniqueness_ratio) p.reconstruction.matcher.uniqueness_ratio = *uniqueness_ratio;
  if (pixel_step) p.reconstruction.pixel_step = *pixel_step;
  if (cell_mean) p.reconstruction.cell_mean = true;
  return p;
}

}  // namespace scanstation::app
