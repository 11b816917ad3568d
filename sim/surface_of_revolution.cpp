#include "sim/surface_of_revolution.h"

#include "core/errors.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace scanstation::sim {

TriangleMesh surface_of_revolution(const Eigen::MatrixX2d& profile, int segments) {
  const Eigen::Index P = profile.rows();
  if (segments < 3) throw InvalidInput("surface of revolution: at least 3 segments");
  if (P < 3 || profile(0, 0) != 0.0 || profile(P - 1, 0) != 0.0)
    throw InvalidInput("surface of revolution: the profile must start and end on the axis (r = 0)");
  for (Eigen::Index i = 1; i + 1 < P; ++i)
    if (!(profile(i, 0) > 0.0)) throw InvalidInput("surface of revolution: inner profile points need r > 0");

  const Eigen::Index rings = P - 2;
  TriangleMesh mesh;
  auto& V = mesh.vertices.positions;
  V.resize(2 + rings * segments, 3);
  const Eigen::Index bottom = 0, top = V.rows() - 1;
  V.row(bottom) << 0, 0, profile(0, 1);
  V.row(top) << 0, 0, profile(P - 1, 1);
  auto id = [&](Eigen::Index ring, Eigen::Index s) { return 1 + ring * segments + (s % segments); };
  for (Eigen::Index ring = 0; ring < rings; ++ring)
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * std::numbers::pi * s / segments;
      V.row(id(ring, s)) << profile(ring + 1, 0) * std::cos(a), profile(ring + 1, 0) * std::sin(a), profile(ring + 1, 1);
    }
  std::vector<Eigen::Vector3i> F;
  for (int s = 0; s < segments; ++s) {
    F.emplace_back(bottom, id(0, s + 1), id(0, s));
    F.emplace_back(top, id(rings - 1, s), id(rings - 1, s + 1));
    for (Eigen::Index ring = 0; ring + 1 < rings; ++ring) {
      F.emplace_back(id(ring, s), id(ring, s + 1), id(ring + 1, s + 1));
      F.emplace_back(id(ring, s), id(ring + 1, s + 1), id(ring + 1, s));
    }
  }
  mesh.faces.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (std::size_t f = 0; f < F.size(); ++f) mesh.faces.row(static_cast<Eigen::Index>(f)) = F[f];
  return mesh;
}

Eigen::MatrixX2d resample_polyline(const Eigen::MatrixX2d& polyline, int samples) {
  const Eigen::Index n = polyline.rows();
  std::vector<double> length(static_cast<std::size_t>(n), 0.0);
  for (Eigen::Index i = 1; i < n; ++i)
    length[static_cast<std::size_t>(i)] = length[static_cast<std::size_t>(i - 1)] + (polyline.row(i) - polyline.row(i - 1)).norm();
  Eigen::MatrixX2d out(samples, 2);
  Eigen::Index segment = 1;
  for (int k = 0; k < samples; ++k) {
    const double s = length.back() * k / (samples - 1);
    while (segment < n - 1 && length[static_cast<std::size_t>(segment)] < s) ++segment;
    const double a = length[static_cast<std::size_t>(segment - 1)], b = length[static_cast<std::size_t>(segment)];
    const double t = b > a ? (s - a) / (b - a) : 0.0;
    out.row(k) = (1.0 - t) * polyline.row(segment - 1) + t * polyline.row(segment);
  }
  out.row(0) = polyline.row(0);
  out.row(samples - 1) = polyline.row(n - 1);
  return out;
}

Eigen::MatrixX2d chalice_profile(int samples) {
  if (samples < 8) throw InvalidInput("chalice profile: at least 8 samples");
  // (r, z) from the centre of the foot, out along the foot, up the stem and
  // the outer bowl to the rim, then down the inner wall to the bowl's floor.
  Eigen::MatrixX2d key(13, 2);
  key << 0.0, 0.0, 1.0, 0.0, 1.0, 0.08, 0.3, 0.2, 0.14, 0.4, 0.14, 1.0, 0.4, 1.2, 0.78, 1.55, 0.9, 2.0, 0.84, 2.0,
      0.7, 1.6, 0.35, 1.32, 0.0, 1.25;
  return resample_polyline(key, samples);
}

}  // namespace scanstation::sim

namespace scanstation::sim {

Eigen::MatrixX2d candlestick_profile(int samples) {
  if (samples < 8) throw InvalidInput("candlestick profile: at least 8 samples");
  // (r, z): foot, base, shaft with two collars and a groove, drip pan,
  // socket, flat top back to the axis.
  Eigen::MatrixX2d key(18, 2);
  key << 0.0, 0.0, 0.8, 0.0, 0.8, 0.12, 0.5, 0.2, 0.28, 0.35, 0.28, 0.7, 0.38, 0.78, 0.28, 0.86, 0.2, 1.2, 0.28, 1.55,
      0.38, 1.62, 0.28, 1.7, 0.3, 1.9, 0.7, 1.95, 0.7, 2.02, 0.22, 2.08, 0.22, 2.3, 0.0, 2.3;
  return resample_polyline(key, samples);
}

}  // namespace scanstation::sim
