#include "acquisition/laser_agreement.h"

#include "acquisition/point_grid.h"
#include "core/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
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

LaserAgreementCheck check_laser_agreement(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, int steps,
                                          Eigen::Index max_compared) {
  LaserAgreementCheck check;
  if (a.rows() == 0 || b.rows() == 0) {
    check.reason = "a laser found no points";
    return check;
  }
  Eigen::MatrixX3d both(a.rows() + b.rows(), 3);
  both << a, b;
  check.diagonal = (both.colwise().maxCoeff() - both.colwise().minCoeff()).norm();
  check.limit = kLaserAgreementLimit * check.diagonal;
  // Stripe spacing where most of b lies: its median distance from the axis.
  Eigen::VectorXd from_axis = b.leftCols<2>().rowwise().norm();
  std::nth_element(from_axis.data(), from_axis.data() + from_axis.size() / 2, from_axis.data() + from_axis.size());
  const double spacing = 2.0 * std::numbers::pi * from_axis(from_axis.size() / 2) / std::max(steps, 1);
  check.radius = 1.6 * spacing;
  if (!(check.radius > 0) || check.radius > kLaserAgreementMaxRadius * check.diagonal) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "stripes %.2f apart at %d steps per turn: too far apart for a local surface fit (scan with more "
                  "steps to check the lasers' agreement)",
                  spacing, steps);
    check.reason = text;
    return check;
  }
  const Eigen::Index stride = std::max<Eigen::Index>(1, (a.rows() + max_compared - 1) / std::max<Eigen::Index>(max_compared, 1));
  Eigen::MatrixX3d sample(((a.rows() + stride - 1) / stride), 3);
  for (Eigen::Index i = 0; i < sample.rows(); ++i) sample.row(i) = a.row(i * stride);
  check.agreement = laser_agreement(sample, b, check.radius);
  if (check.agreement.compared == 0) {
    check.reason = "no point of laser 0 has enough of laser 1's stripes around it";
    return check;
  }
  check.checked = true;
  check.agree = check.agreement.median_distance <= check.limit;
  return check;
}

nlohmann::json to_json(const LaserAgreementCheck& check) {
  nlohmann::json document = {{"checked", check.checked},
                             {"agree", check.agree},
                             {"median_distance", check.agreement.median_distance},
                             {"p90_distance", check.agreement.p90_distance},
                             {"compared", check.agreement.compared},
                             {"radius", check.radius},
                             {"limit", check.limit},
                             {"diagonal", check.diagonal}};
  if (!check.reason.empty()) document["reason"] = check.reason;
  return document;
}

std::string laser_disagreement_message(const LaserAgreementCheck& check) {
  if (!check.checked || check.agree) return "";
  char text[400];
  std::snprintf(text, sizeof text,
                "lasers 0 and 1 disagree: their clouds lie %.3f apart (median; limit %.3f, 0.1%% of the scan's "
                "diagonal) — two shifted copies of the object. A laser plane is off: recalibrate it "
                "(`scanstation calibrate laser --force`)",
                check.agreement.median_distance, check.limit);
  return text;
}

}  // namespace scanstation::acquisition
