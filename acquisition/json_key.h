// Reading one numeric or true/false key of a parameters object (laser_scan_parameters.h,
// stereo_scan_parameters.h) with the error naming where it is.
#pragma once

#include "core/errors.h"

#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <vector>

namespace scanstation::acquisition {

/// Reads `object`[key] into `target` when present; `valid` judges the value
/// read (InvalidInput "where.key: expected …, got …" otherwise). An absent
/// key keeps `target` and is listed in `missing` (when given).
template <typename T, typename Valid>
void read_key(const nlohmann::json& object, const char* key, const std::string& where, T& target, Valid valid,
              const char* expected, std::vector<std::string>* missing) {
  const auto it = object.find(key);
  if (it == object.end()) {
    if (missing) missing->push_back(where + "." + key);
    return;
  }
  const bool right_type = std::is_same_v<T, bool> ? it->is_boolean()
                          : std::is_integral_v<T> ? it->is_number_integer()
                                                  : it->is_number();
  if (!right_type || !valid(it->template get<T>()))
    throw InvalidInput(where + "." + key + ": expected " + expected + ", got " + it->dump());
  target = it->template get<T>();
}

/// A recorded least point spacing (point_spacing.h): 0, or a distance the
/// spacing filter can number its cubes by for any station's points.
inline bool valid_min_spacing(double v) { return v == 0 || (v >= 1e-6 && v <= 1e9); }
inline constexpr const char* kMinSpacingRange = "0 (every point) or a distance from 1e-6 to 1e9";

}  // namespace scanstation::acquisition
