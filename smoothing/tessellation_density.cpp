#include "smoothing/tessellation_density.h"

#include "core/errors.h"
#include "smoothing/blockwise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace scanstation {

namespace {

using Weights = std::array<double, 10>;  // Bernstein weights of b300 … b003 at one parameter

Weights bernstein(const Barycentric& uvw) {
  static constexpr std::array<double, 4> kFactorial = {1, 1, 2, 6};
  Weights w{};
  for (int i = 0; i <= 3; ++i)
    for (int k = 0; i + k <= 3; ++k) {
      const int j = 3 - i - k;
      w[static_cast<std::size_t>(control_index(i, j, k))] =
          6.0 / (kFactorial[i] * kFactorial[j] * kFactorial[k]) * std::pow(uvw[0], i) * std::pow(uvw[1], j) *
          std::pow(uvw[2], k);
    }
  return w;
}

Eigen::Vector3d combine(const CubicTriangle& patch, const Weights& w) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < 10; ++i) p += w[i] * patch[i];
  return p;
}

// What one density samples, the same for every patch: the grid's points
// (tessellate()'s numbering) and, per triangle of the grid, its corners and
// the weights at its centroid and edge midpoints.
struct Stencil {
  std::vector<Weights> grid;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<Weights, 4>> samples;  // centroid, then the midpoints of edges 01, 12, 20

  explicit Stencil(int n) {
    const auto parameter = [n](int a, int b) { return Barycentric(double(n - a - b) / n, double(a) / n, double(b) / n); };
    const auto at = [n](int a, int b) { return a * (2 * n + 3 - a) / 2 + b; };
    for (int a = 0; a <= n; ++a)
      for (int b = 0; a + b <= n; ++b) grid.push_back(bernstein(parameter(a, b)));
    const auto add = [&](std::array<int, 2> p, std::array<int, 2> q, std::array<int, 2> r) {
      triangles.push_back({at(p[0], p[1]), at(q[0], q[1]), at(r[0], r[1])});
      const Barycentric x = parameter(p[0], p[1]), y = parameter(q[0], q[1]), z = parameter(r[0], r[1]);
      samples.push_back({bernstein((x + y + z) / 3), bernstein((x + y) / 2), bernstein((y + z) / 2),
                         bernstein((z + x) / 2)});
    };
    for (int a = 0; a < n; ++a)
      for (int b = 0; a + b < n; ++b) {
        add({a, b}, {a + 1, b}, {a, b + 1});
        if (a + b < n - 1) add({a + 1, b}, {a + 1, b + 1}, {a, b + 1});
      }
  }

  // `scale` (a power of two, surface_scale) brings the gaps into the range
  // where their squares neither overflow nor underflow; the answer is
  // scaled back, exactly.
  double deviation(const CubicTriangle& patch, std::vector<Eigen::Vector3d>& points, const SurfaceScale& scale) const {
    points.resize(grid.size());
    for (std::size_t g = 0; g < grid.size(); ++g) points[g] = combine(patch, grid[g]);
    double largest = 0;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const Eigen::Vector3d& p = points[static_cast<std::size_t>(triangles[t][0])];
      const Eigen::Vector3d& q = points[static_cast<std::size_t>(triangles[t][1])];
      const Eigen::Vector3d& r = points[static_cast<std::size_t>(triangles[t][2])];
      const std::array<Eigen::Vector3d, 4> flat = {(p + q + r) / 3, (p + q) / 2, (q + r) / 2, (r + p) / 2};
      for (std::size_t s = 0; s < 4; ++s)
        largest = std::max(largest, ((combine(patch, samples[t][s]) - flat[s]) * scale.down).squaredNorm());
    }
    return std::sqrt(largest) * scale.up;
  }
};

// The control points' bounding box, as half its widths (finite wherever the
// points are, even where the widths themselves would overflow).
Eigen::Vector3d half_widths(const BezierSurface& surface) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const CubicTriangle& patch : surface.patches)
    for (const Eigen::Vector3d& b : patch) {
      low = low.cwiseMin(b);
      high = high.cwiseMax(b);
    }
  return high / 2 - low / 2;
}

}  // namespace

SurfaceScale surface_scale(const BezierSurface& surface) {
  SurfaceScale scale;
  if (surface.patches.empty()) return scale;
  const double widest = half_widths(surface).maxCoeff();
  int exponent = 0;
  if (widest > 0 && std::isfinite(widest)) std::frexp(widest, &exponent);
  // Within 2^±100 every square of a gap is a normal number: no scaling,
  // the same arithmetic as ever. Beyond, the widest half width becomes
  // [1/2, 1) (2^±exponent stays a normal double: |exponent| ≤ 1024).
  if (std::abs(exponent) > 100) {
    scale.down = std::ldexp(1.0, -exponent);
    scale.up = std::ldexp(1.0, exponent);
  }
  return scale;
}

double tessellation_deviation(const BezierSurface& surface, int density) {
  if (density < 1) throw InvalidInput("--density must be at least 1, got " + std::to_string(density));
  const Stencil stencil(density);
  const SurfaceScale scale = surface_scale(surface);
  // The largest of maxima: the same in any order, on any number of threads.
  const std::vector<double> partial =
      blockwise<double>(surface.patches.size(), 1024, [&](std::size_t begin, std::size_t end, double& largest) {
        std::vector<Eigen::Vector3d> points;
        for (std::size_t p = begin; p < end; ++p)
          largest = std::max(largest, stencil.deviation(surface.patches[p], points, scale));
      });
  return partial.empty() ? 0.0 : *std::max_element(partial.begin(), partial.end());
}

ChosenTessellation adaptive_tessellation(const BezierSurface& surface, double tolerance, int max_density) {
  if (!(tolerance >= 0) || !std::isfinite(tolerance))
    throw InvalidInput("the tessellation tolerance must be a finite number at least 0, got " + std::to_string(tolerance));
  if (max_density < 1) throw InvalidInput("the largest tessellation density must be at least 1");
  std::vector<Stencil> stencils;
  for (int n = 1; n <= max_density; ++n) stencils.emplace_back(n);
  const SurfaceScale scale = surface_scale(surface);
  struct Partial {
    double deviation = 0;
    std::size_t above = 0;
  };
  std::vector<int> density(surface.patches.size());
  const std::vector<Partial> partial =
      blockwise<Partial>(surface.patches.size(), 1024, [&](std::size_t begin, std::size_t end, Partial& out) {
        std::vector<Eigen::Vector3d> points;
        for (std::size_t p = begin; p < end; ++p) {
          int n = 1;
          double deviation = stencils[0].deviation(surface.patches[p], points, scale);
          while (deviation > tolerance && n < max_density)
            deviation = stencils[static_cast<std::size_t>(n++)].deviation(surface.patches[p], points, scale);
          density[p] = n;
          out.deviation = std::max(out.deviation, deviation);
          out.above += deviation > tolerance;
        }
      });
  ChosenTessellation chosen;
  chosen.tolerance = tolerance;
  for (const Partial& part : partial) {
    chosen.deviation = std::max(chosen.deviation, part.deviation);
    chosen.above += part.above;
  }
  chosen.largest_density = density.empty() ? 1 : *std::max_element(density.begin(), density.end());
  chosen.plan = plan_from_densities(surface, std::move(density));
  return chosen;
}

double default_tessellation_tolerance(const BezierSurface& surface) {
  if (surface.patches.empty()) return 0;
  // 2e-4 of the diagonal, from the half widths scaled as the deviations are
  // (the diagonal of coordinates near 1e160 overflows, of those near
  // 1e-160 underflows to 0); bit for bit 2e-4 · |high − low| otherwise.
  const SurfaceScale scale = surface_scale(surface);
  return 4e-4 * ((half_widths(surface) * scale.down).norm() * scale.up);
}

ChosenTessellation choose_tessellation(const BezierSurface& surface, std::optional<int> fixed) {
  const double tolerance = default_tessellation_tolerance(surface);
  if (!fixed) return adaptive_tessellation(surface, tolerance, kAutomaticDensityLimit);
  // N segments per edge make N² triangles a patch: --density 64 over the
  // 300k patches of a refined mesh asked for 1.2e9 (hours, tens of GB).
  const double faces = static_cast<double>(surface.patches.size()) * *fixed * *fixed;
  if (faces > kMostFixedFaces) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "--density %d over %zu patches would write %.3g triangles, more than %.0e: choose a smaller "
                  "density, or auto",
                  *fixed, surface.patches.size(), faces, kMostFixedFaces);
    throw InvalidInput(text);
  }
  ChosenTessellation chosen;
  chosen.plan = uniform_plan(surface, *fixed);
  chosen.automatic = false;
  chosen.largest_density = *fixed;
  chosen.deviation = tessellation_deviation(surface, *fixed);
  chosen.tolerance = tolerance;
  return chosen;
}

nlohmann::json describe(const ChosenTessellation& chosen) {
  nlohmann::json out = {{"automatic", chosen.automatic}};
  out[chosen.automatic ? "largest_density" : "density"] = chosen.largest_density;
  out["deviation"] = chosen.deviation;
  out["tolerance"] = chosen.tolerance;
  if (chosen.automatic) out["patches_above_tolerance"] = chosen.above;
  out["faces"] = chosen.plan.face_count();
  return out;
}

}  // namespace scanstation
