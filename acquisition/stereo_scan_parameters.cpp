#include "acquisition/stereo_scan_parameters.h"

#include "acquisition/json_key.h"

#include <cmath>

namespace scanstation::acquisition {

using nlohmann::json;

StereoScanParameters stereo_scan_defaults() {
  StereoScanParameters p;
  // Eight pixels apart: at 640×480 about 2 mm between points on the object
  // — the views of neighbouring steps overlap, so the cloud is denser still
  // — and a few thousand points per step for the live boundary.
  p.reconstruction.pixel_step = 8;
  return p;
}

json to_json(const StereoScanParameters& p) {
  const StereoReconstructionOptions& r = p.reconstruction;
  const StereoOptions& m = r.matcher;
  return {{"block_size", m.block_size},
          {"uniqueness_ratio", m.uniqueness_ratio},
          {"speckle_window_size", m.speckle_window_size},
          {"speckle_range", m.speckle_range},
          {"left_right_tolerance", m.left_right_tolerance},
          {"minimum_height", r.minimum_height},
          {"discontinuity", r.discontinuity},
          {"minimum_texture", r.minimum_texture},
          {"pixel_step", r.pixel_step},
          {"cell_mean", r.cell_mean},
          {"volume_radius", p.volume_radius},
          {"volume_height", p.volume_height},
          {"num_disparities", p.num_disparities},
          {"outlier_radius", p.outlier_radius},
          {"outlier_neighbours", p.outlier_neighbours},
          {"min_spacing", p.min_spacing}};
}

StereoScanParameters stereo_scan_parameters_from_json(const json& value, const std::string& where,
                                                      const StereoScanParameters& base,
                                                      std::vector<std::string>* missing) {
  if (!value.is_object()) throw InvalidInput(where + ": expected an object");
  StereoScanParameters p = base;
  StereoReconstructionOptions& r = p.reconstruction;
  StereoOptions& m = r.matcher;
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0; };
  const auto at_least = [](int low) { return [low](int v) { return v >= low; }; };
  read_key(value, "block_size", where, m.block_size, [](int v) { return v >= 1 && v % 2 == 1 && v <= 51; },
           "an odd integer in 1..51", missing);
  read_key(value, "uniqueness_ratio", where, m.uniqueness_ratio, [](int v) { return v >= 0 && v <= 100; },
           "an integer in 0..100", missing);
  read_key(value, "speckle_window_size", where, m.speckle_window_size, at_least(0), "an integer ≥ 0", missing);
  read_key(value, "speckle_range", where, m.speckle_range, at_least(0), "an integer ≥ 0", missing);
  read_key(value, "left_right_tolerance", where, m.left_right_tolerance, positive, "a positive number", missing);
  read_key(value, "minimum_height", where, r.minimum_height, [](double v) { return std::isfinite(v); }, "a number",
           missing);
  read_key(value, "discontinuity", where, r.discontinuity, [](double v) { return std::isfinite(v); },
           "a number (≤ 0 = off)", missing);
  read_key(value, "minimum_texture", where, r.minimum_texture, non_negative, "a number ≥ 0", missing);
  read_key(value, "pixel_step", where, r.pixel_step, at_least(1), "an integer ≥ 1", missing);
  read_key(value, "cell_mean", where, r.cell_mean, [](bool) { return true; }, "true or false", nullptr);
  read_key(value, "volume_radius", where, p.volume_radius, positive, "a positive number", missing);
  read_key(value, "volume_height", where, p.volume_height, positive, "a positive number", missing);
  read_key(value, "num_disparities", where, p.num_disparities,
           [](int v) { return v >= 0 && v % 16 == 0 && v <= 1024; }, "0 (fitted) or a multiple of 16 up to 1024",
           nullptr);
  read_key(value, "outlier_radius", where, p.outlier_radius, non_negative, "a number ≥ 0 (0 = off)", missing);
  read_key(value, "outlier_neighbours", where, p.outlier_neighbours, at_least(1), "an integer ≥ 1", missing);
  read_key(value, "min_spacing", where, p.min_spacing, valid_min_spacing, kMinSpacingRange, nullptr);
  return p;
}

}  // namespace scanstation::acquisition
