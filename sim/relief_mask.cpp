#include "sim/relief_mask.h"

#include "core/errors.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace scanstation::sim {

namespace {

constexpr double kHalfWidth = 0.7;   // ellipse semi-axis along x (half height 1 along y)
constexpr double kDomeHeight = 0.35;
constexpr double kBackDepth = 0.12;

double bump(double x, double y, double cx, double cy, double sx, double sy) {
  const double u = (x - cx) / sx, v = (y - cy) / sy;
  return std::exp(-0.5 * (u * u + v * v));
}

// Squared elliptic radius: 0 at the centre, 1 on the rim.
double rim_distance2(double x, double y) { return (x / kHalfWidth) * (x / kHalfWidth) + y * y; }

}  // namespace

double relief_mask_height(double x, double y) {
  const double rho2 = rim_distance2(x, y);
  if (rho2 >= 1.0) return 0.0;
  const double features = 0.22 * bump(x, y, 0.0, -0.02, 0.07, 0.2)        // nose
                          + 0.05 * bump(x, y, 0.0, 0.33, 0.3, 0.05)       // brow ridge
                          - 0.10 * bump(x, y, -0.24, 0.2, 0.09, 0.07)     // left eye socket
                          - 0.10 * bump(x, y, 0.24, 0.2, 0.09, 0.07)      // right eye socket
                          + 0.04 * bump(x, y, 0.0, -0.4, 0.14, 0.035)     // lips
                          - 0.03 * bump(x, y, 0.0, -0.45, 0.12, 0.015)    // mouth
                          + 0.05 * bump(x, y, 0.0, -0.75, 0.12, 0.08);    // chin
  // The dome meets the rim vertically; the features fade out before it.
  return kDomeHeight * std::sqrt(1.0 - rho2) + features * (1.0 - rho2) * (1.0 - rho2);
}

TriangleMesh relief_mask(int rings, int segments) {
  if (rings < 2 || segments < 3) throw InvalidInput("relief mask: at least 2 rings and 3 segments");
  // Vertex layout: front centre, front rings 1..rings-1, the shared rim ring,
  // back rings rings-1..1, back centre.
  const int ring_count = 2 * rings - 1;
  TriangleMesh mesh;
  auto& V = mesh.vertices.positions;
  V.resize(2 + static_cast<Eigen::Index>(ring_count) * segments, 3);
  const Eigen::Index front = 0, back = V.rows() - 1;
  V.row(front) << 0.0, 0.0, relief_mask_height(0.0, 0.0);
  V.row(back) << 0.0, 0.0, -kBackDepth;
  auto id = [&](int ring, int s) { return 1 + static_cast<Eigen::Index>(ring) * segments + (s % segments); };
  for (int ring = 0; ring < ring_count; ++ring) {
    const bool on_front = ring < rings - 1, on_rim = ring == rings - 1;
    const int k = on_front || on_rim ? ring + 1 : ring_count - ring;  // radial index 1..rings
    const double rho = static_cast<double>(k) / rings;
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * std::numbers::pi * s / segments;
      const double x = kHalfWidth * rho * std::cos(a), y = rho * std::sin(a);
      const double z = on_rim ? 0.0 : on_front ? relief_mask_height(x, y) : -kBackDepth * std::sqrt(1.0 - rho * rho);
      V.row(id(ring, s)) << x, y, z;
    }
  }
  std::vector<Eigen::Vector3i> F;
  for (int s = 0; s < segments; ++s) {
    F.emplace_back(front, id(0, s), id(0, s + 1));
    F.emplace_back(back, id(ring_count - 1, s + 1), id(ring_count - 1, s));
    for (int ring = 0; ring + 1 < ring_count; ++ring) {
      F.emplace_back(id(ring, s), id(ring + 1, s), id(ring + 1, s + 1));
      F.emplace_back(id(ring, s), id(ring + 1, s + 1), id(ring, s + 1));
    }
  }
  mesh.faces.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (std::size_t f = 0; f < F.size(); ++f) mesh.faces.row(static_cast<Eigen::Index>(f)) = F[f];
  return mesh;
}

}  // namespace scanstation::sim
