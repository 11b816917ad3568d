#include "sim/sampling.h"

#include "core/errors.h"
#include "sim/random.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace scanstation::sim {

namespace {

constexpr std::uint64_t kNoiseStream = 0x9e3779b97f4a7c15ULL;

void check_noise(double noise) {
  if (!(noise >= 0.0) || !std::isfinite(noise)) throw InvalidInput("sampling: noise must be a finite value ≥ 0");
}

// Cumulative weights; a uniform draw picks the element whose interval holds it.
std::size_t pick(const std::vector<double>& cumulative, double u) {
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u * cumulative.back());
  return std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), cumulative.size() - 1);
}

}  // namespace

PointCloud sample_surface(const TriangleMesh& mesh, Eigen::Index count, std::uint64_t seed, double noise) {
  check_noise(noise);
  const auto& V = mesh.vertices.positions;
  std::vector<double> cumulative(static_cast<std::size_t>(mesh.face_count()));
  double total = 0.0;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const Eigen::Vector3d a = V.row(mesh.faces(f, 0)), b = V.row(mesh.faces(f, 1)), c = V.row(mesh.faces(f, 2));
    total += 0.5 * (b - a).cross(c - a).norm();
    cumulative[static_cast<std::size_t>(f)] = total;
  }
  if (!(total > 0.0)) throw InvalidInput("sample_surface: the mesh has no area to sample");
  // Noise from its own stream: the same seed gives the same clean samples
  // with or without noise.
  Random random(seed), jitter(seed ^ kNoiseStream);
  PointCloud cloud;
  cloud.positions.resize(count, 3);
  cloud.normals.resize(count, 3);
  for (Eigen::Index i = 0; i < count; ++i) {
    const auto f = static_cast<Eigen::Index>(pick(cumulative, random.uniform()));
    const Eigen::Vector3d a = V.row(mesh.faces(f, 0)), b = V.row(mesh.faces(f, 1)), c = V.row(mesh.faces(f, 2));
    // Uniform barycentric coordinates by folding the unit square.
    double s = random.uniform(), t = random.uniform();
    if (s + t > 1.0) s = 1.0 - s, t = 1.0 - t;
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    cloud.positions.row(i) = a + s * (b - a) + t * (c - a) + noise * jitter.normal() * n;
    cloud.normals.row(i) = n;
  }
  return cloud;
}

Eigen::MatrixX2d sample_outline(const Polygon2& outline, Eigen::Index count, std::uint64_t seed, double noise) {
  check_noise(noise);
  const Eigen::Index n = outline.size();
  if (n < 3) throw InvalidInput("sample_outline: the outline needs at least 3 vertices");
  std::vector<double> cumulative(static_cast<std::size_t>(n));
  double total = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    total += (outline.vertices.row((i + 1) % n) - outline.vertices.row(i)).norm();
    cumulative[static_cast<std::size_t>(i)] = total;
  }
  if (!(total > 0.0)) throw InvalidInput("sample_outline: the outline has no length");
  Random random(seed);
  // Sorted arc-length positions keep the samples in boundary order.
  std::vector<double> at(static_cast<std::size_t>(count));
  for (auto& s : at) s = random.uniform() * total;
  std::sort(at.begin(), at.end());
  Eigen::MatrixX2d points(count, 2);
  std::size_t edge = 0;
  for (Eigen::Index k = 0; k < count; ++k) {
    const double s = at[static_cast<std::size_t>(k)];
    while (edge + 1 < cumulative.size() && cumulative[edge] < s) ++edge;
    const double start = edge == 0 ? 0.0 : cumulative[edge - 1];
    const double length = cumulative[edge] - start;
    const double t = length > 0.0 ? (s - start) / length : 0.0;
    const auto i = static_cast<Eigen::Index>(edge);
    points.row(k) = (1.0 - t) * outline.vertices.row(i) + t * outline.vertices.row((i + 1) % n);
  }
  return noise > 0.0 ? Eigen::MatrixX2d(add_gaussian_noise(points, noise, seed ^ kNoiseStream)) : points;
}

Eigen::MatrixXd add_gaussian_noise(const Eigen::MatrixXd& points, double sigma, std::uint64_t seed) {
  check_noise(sigma);
  Random random(seed);
  Eigen::MatrixXd out = points;
  for (Eigen::Index i = 0; i < out.rows(); ++i)
    for (Eigen::Index c = 0; c < out.cols(); ++c) out(i, c) += sigma * random.normal();
  return out;
}

}  // namespace scanstation::sim
