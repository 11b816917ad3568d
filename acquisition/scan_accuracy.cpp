#include "acquisition/scan_accuracy.h"

#include "core/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace scanstation::acquisition {

SphereFit fit_sphere(const Eigen::MatrixX3d& points) {
  const Eigen::Index n = points.rows();
  if (n < 4) throw InvalidInput("sphere fit: at least 4 points are needed");
  Eigen::MatrixX4d A(n, 4);
  A << 2.0 * points, Eigen::VectorXd::Ones(n);
  const Eigen::VectorXd b = points.rowwise().squaredNorm();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixX4d> qr(A);
  if (qr.rank() < 4) throw InvalidInput("sphere fit: the points are coplanar");
  const Eigen::Vector4d x = qr.solve(b);
  SphereFit fit;
  fit.centre = x.head<3>();
  fit.radius = std::sqrt(std::max(0.0, x(3) + fit.centre.squaredNorm()));
  Eigen::VectorXd residual(n);
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::MatrixX4d J(n, 4);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3d d = points.row(i).transpose() - fit.centre;
      const double length = d.norm();
      residual(i) = length - fit.radius;
      J.row(i) << -d.transpose() / length, -1.0;
    }
    const Eigen::Vector4d step = J.colPivHouseholderQr().solve(-residual);
    fit.centre += step.head<3>();
    fit.radius += step(3);
    if (step.norm() < 1e-12 * fit.radius) break;
  }
  for (Eigen::Index i = 0; i < n; ++i) residual(i) = (points.row(i).transpose() - fit.centre).norm() - fit.radius;
  fit.rms = std::sqrt(residual.squaredNorm() / static_cast<double>(n));
  fit.form_error = residual.maxCoeff() - residual.minCoeff();
  return fit;
}

double coverage(const Eigen::MatrixX3d& surface_samples, const Eigen::MatrixX3d& scanned, double radius) {
  if (!(radius > 0)) throw InvalidInput("coverage: the radius must be positive");
  if (surface_samples.rows() == 0) return 0.0;
  // Scanned points hashed into cubes of side `radius`: a neighbour within
  // `radius` sits in one of the 27 cubes around a sample.
  const auto cell = [radius](const Eigen::Vector3d& p) {
    return Eigen::Vector3i((p / radius).array().floor().cast<int>());
  };
  const auto key = [](const Eigen::Vector3i& c) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.x())) * 73856093u) ^
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.y())) * 19349663u) ^
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.z())) * 83492791u);
  };
  std::unordered_multimap<std::uint64_t, Eigen::Index> grid;
  for (Eigen::Index i = 0; i < scanned.rows(); ++i) grid.emplace(key(cell(scanned.row(i))), i);
  Eigen::Index covered = 0;
  for (Eigen::Index s = 0; s < surface_samples.rows(); ++s) {
    const Eigen::Vector3d p = surface_samples.row(s);
    const Eigen::Vector3i c = cell(p);
    bool near = false;
    for (int dx = -1; dx <= 1 && !near; ++dx)
      for (int dy = -1; dy <= 1 && !near; ++dy)
        for (int dz = -1; dz <= 1 && !near; ++dz) {
          const auto [first, last] = grid.equal_range(key(c + Eigen::Vector3i(dx, dy, dz)));
          for (auto it = first; it != last && !near; ++it) near = (scanned.row(it->second).transpose() - p).norm() <= radius;
        }
    covered += near;
  }
  return static_cast<double>(covered) / static_cast<double>(surface_samples.rows());
}

}  // namespace scanstation::acquisition
