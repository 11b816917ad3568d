#include "acquisition/scan_accuracy.h"

#include "acquisition/point_grid.h"
#include "core/errors.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
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
  const PointGrid grid(scanned, radius);
  Eigen::Index covered = 0;
  for (Eigen::Index s = 0; s < surface_samples.rows(); ++s) covered += grid.any_within(surface_samples.row(s));
  return static_cast<double>(covered) / static_cast<double>(surface_samples.rows());
}

double area_coverage(const TriangleMesh& surface, const Eigen::MatrixX3d& scanned, double radius) {
  if (!(radius > 0)) throw InvalidInput("coverage: the radius must be positive");
  const PointGrid grid(scanned, radius);
  const auto& V = surface.vertices.positions;
  double seen = 0, all = 0;
  for (Eigen::Index f = 0; f < surface.face_count(); ++f) {
    const Eigen::Vector3d a = V.row(surface.faces(f, 0)), b = V.row(surface.faces(f, 1)), c = V.row(surface.faces(f, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    all += area;
    if (grid.any_within((a + b + c) / 3.0)) seen += area;
  }
  return all > 0 ? seen / all : 0.0;
}

}  // namespace scanstation::acquisition
