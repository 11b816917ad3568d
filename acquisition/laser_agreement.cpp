#include "acquisition/laser_agreement.h"

#include "acquisition/point_grid.h"
#include "core/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace scanstation::acquisition {

LaserAgreement laser_agreement(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, double radius) {
  if (!(radius > 0)) throw InvalidInput("laser agreement: the neighbourhood radius must be positive");
  const PointGrid grid(b, radius);
  std::vector<double> distance;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const Eigen::Vector3d p = a.row(i);
    const std::vector<Eigen::Index> near = grid.within(p);
    if (near.size() < 6) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Index j : near) mean += b.row(j).transpose();
    mean /= static_cast<double>(near.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const Eigen::Index j : near) {
      const Eigen::Vector3d d = b.row(j).transpose() - mean;
      covariance += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    const Eigen::Vector3d u = eigen.eigenvectors().col(2), v = eigen.eigenvectors().col(1), n = eigen.eigenvectors().col(0);
    // Height over the neighbours' tangent plane, fitted by a quadric: the
    // stripes of B are a few millimetres apart, over which the surface bends.
    Eigen::MatrixXd design(static_cast<Eigen::Index>(near.size()), 6);
    Eigen::VectorXd height(static_cast<Eigen::Index>(near.size()));
    for (std::size_t k = 0; k < near.size(); ++k) {
      const Eigen::Vector3d d = b.row(near[k]).transpose() - mean;
      const double x = u.dot(d) / radius, y = v.dot(d) / radius;
      design.row(static_cast<Eigen::Index>(k)) << 1, x, y, x * x, x * y, y * y;
      height(static_cast<Eigen::Index>(k)) = n.dot(d);
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
    qr.setThreshold(1e-6);
    if (qr.rank() < 6) continue;  // neighbours on one or two stripes: no surface to compare with
    const Eigen::VectorXd c = qr.solve(height);
    const Eigen::Vector3d d = p - mean;
    const double x = u.dot(d) / radius, y = v.dot(d) / radius;
    distance.push_back(std::abs(n.dot(d) - (c(0) + c(1) * x + c(2) * y + c(3) * x * x + c(4) * x * y + c(5) * y * y)));
  }
  LaserAgreement agreement;
  if (distance.empty()) return agreement;
  std::sort(distance.begin(), distance.end());
  agreement.median_distance = distance[distance.size() / 2];
  agreement.p90_distance = distance[distance.size() * 9 / 10];
  agreement.compared = static_cast<double>(distance.size()) / static_cast<double>(a.rows());
  return agreement;
}

}  // namespace scanstation::acquisition
