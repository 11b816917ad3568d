// Seeded random numbers that are the same on every machine and standard
// library: std::mt19937_64 is specified bit for bit, but the std
// distributions are not, so the conversions are written out here.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>

namespace scanstation::sim {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Standard normal (Box–Muller).
  double normal() {
    const double u = 1.0 - uniform();  // (0, 1]: log stays finite
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * uniform());
  }
  /// Two independent standard normals for bulk noise (Marsaglia's polar
  /// method: a point uniform in the unit disc from the two 32-bit halves of
  /// one draw, 1.27 draws on average, no trigonometry). With 32-bit
  /// coordinates the tails end at 9.3 standard deviations.
  std::pair<double, double> normal_pair() {
    for (;;) {
      const std::uint64_t bits = engine_();
      const double x = static_cast<double>(bits >> 32) * 0x1.0p-31 - 1.0;
      const double y = static_cast<double>(bits & 0xFFFFFFFFu) * 0x1.0p-31 - 1.0;
      const double s = x * x + y * y;
      if (s >= 1.0 || s == 0.0) continue;
      const double f = std::sqrt(-2.0 * std::log(s) / s);
      return {x * f, y * f};
    }
  }
  /// Uniform integer in [0, n), n > 0.
  std::uint64_t below(std::uint64_t n) { return static_cast<std::uint64_t>(uniform() * static_cast<double>(n)); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace scanstation::sim
