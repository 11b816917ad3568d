#include "acquisition/laser_scan_parameters.h"

#include "acquisition/json_key.h"
#include "core/errors.h"

#include <cmath>
#include <limits>

namespace scanstation::acquisition {

namespace {

using nlohmann::json;

bool finite_non_negative(double v) { return std::isfinite(v) && v >= 0; }

}  // namespace

std::string peak_fit_name(PeakFit fit) {
  switch (fit) {
    case PeakFit::centre_of_mass: return "centre_of_mass";
    case PeakFit::parabolic: return "parabolic";
    case PeakFit::gaussian: break;
  }
  return "gaussian";
}

PeakFit parse_peak_fit(const std::string& name) {
  for (const PeakFit fit : {PeakFit::gaussian, PeakFit::centre_of_mass, PeakFit::parabolic})
    if (peak_fit_name(fit) == name) return fit;
  throw InvalidInput("peak fit: expected gaussian, centre_of_mass or parabolic, got '" + name + "'");
}

json to_json(const LaserScanParameters& p) {
  const LaserLineOptions& l = p.line;
  const LaserTriangulationOptions& t = p.triangulation;
  return {{"peak_fit", peak_fit_name(l.fit)},
          {"threshold_sigmas", l.threshold_sigmas},
          {"minimum_contrast", l.minimum_contrast},
          {"minimum_width", l.minimum_width},
          {"maximum_width", l.maximum_width},
          {"saturation", l.saturation},
          {"double_peak_ratio", l.double_peak_ratio},
          {"region", json::array({l.region.x, l.region.y, l.region.width, l.region.height})},
          {"minimum_height", t.minimum_height},
          {"maximum_radius", std::isfinite(t.maximum_radius) ? json(t.maximum_radius) : json(nullptr)},
          {"minimum_incidence", t.minimum_incidence},
          {"outlier_radius", p.outlier_radius},
          {"outlier_neighbours", p.outlier_neighbours},
          {"min_spacing", p.min_spacing},
          {"row_step", p.row_step}};
}

LaserScanParameters laser_scan_parameters_from_json(const json& value, const std::string& where,
                                                    const LaserScanParameters& base,
                                                    std::vector<std::string>* missing) {
  if (!value.is_object()) throw InvalidInput(where + ": expected an object");
  LaserScanParameters p = base;
  LaserLineOptions& l = p.line;
  LaserTriangulationOptions& t = p.triangulation;
  if (const auto it = value.find("peak_fit"); it != value.end()) {
    if (!it->is_string()) throw InvalidInput(where + ".peak_fit: expected a string");
    try {
      l.fit = parse_peak_fit(it->get<std::string>());
    } catch (const InvalidInput& e) {
      throw InvalidInput(where + ".peak_fit: " + e.what());
    }
  } else if (missing) {
    missing->push_back(where + ".peak_fit");
  }
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  read_key(value, "threshold_sigmas", where, l.threshold_sigmas, finite_non_negative, "a number ≥ 0", missing);
  read_key(value, "minimum_contrast", where, l.minimum_contrast, finite_non_negative, "a number ≥ 0", missing);
  read_key(value, "minimum_width", where, l.minimum_width, [](int v) { return v >= 1; }, "an integer ≥ 1", missing);
  read_key(value, "maximum_width", where, l.maximum_width, [](int v) { return v >= 1; }, "an integer ≥ 1", missing);
  if (l.minimum_width > l.maximum_width)
    throw InvalidInput(where + ".minimum_width (" + std::to_string(l.minimum_width) + ") is greater than maximum_width (" +
                       std::to_string(l.maximum_width) + "): no stripe could be kept");
  read_key(value, "saturation", where, l.saturation, [](int v) { return v >= 1 && v <= 255; }, "1..255", missing);
  read_key(value, "double_peak_ratio", where, l.double_peak_ratio, positive, "a positive number", missing);
  if (const auto it = value.find("region"); it != value.end()) {
    if (!it->is_array() || it->size() != 4 || !std::all_of(it->begin(), it->end(), [](const json& v) {
          return v.is_number_integer() && v.get<long long>() >= 0;
        }))
      throw InvalidInput(where + ".region: expected [x, y, width, height] of integers ≥ 0");
    l.region = cv::Rect((*it)[0].get<int>(), (*it)[1].get<int>(), (*it)[2].get<int>(), (*it)[3].get<int>());
  } else if (missing) {
    missing->push_back(where + ".region");
  }
  read_key(value, "minimum_height", where, t.minimum_height, [](double v) { return std::isfinite(v); }, "a number",
           missing);
  if (const auto it = value.find("maximum_radius"); it != value.end() && it->is_null()) {
    t.maximum_radius = std::numeric_limits<double>::infinity();
  } else {
    read_key(value, "maximum_radius", where, t.maximum_radius, positive, "a positive number or null", missing);
  }
  read_key(value, "minimum_incidence", where, t.minimum_incidence, [](double v) { return v >= 0 && v < 1; },
           "a number in [0, 1)", missing);
  read_key(value, "outlier_radius", where, p.outlier_radius, finite_non_negative, "a number ≥ 0 (0 = off)", missing);
  read_key(value, "outlier_neighbours", where, p.outlier_neighbours, [](int v) { return v >= 1; }, "an integer ≥ 1",
           missing);
  read_key(value, "min_spacing", where, p.min_spacing, valid_min_spacing, kMinSpacingRange, nullptr);
  read_key(value, "row_step", where, p.row_step, [](int v) { return v >= 1; }, "an integer ≥ 1", missing);
  return p;
}

}  // namespace scanstation::acquisition
