#include "acquisition/laser_agreement.h"

#include "acquisition/point_grid.h"
#include "core/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numbers>
#include <vector>

namespace scanstation::acquisition {

LaserAgreement laser_agreement(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, double radius) {
  if (!(radius > 0)) throw InvalidInput("laser agreement: the neighbourhood radius must be positive");
  const PointGrid grid(b, radius);
  const Eigen::RowVector3d centroid = b.colwise().mean();
  std::vector<double> distance, signed_distance;
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
    const double off = n.dot(d) - (c(0) + c(1) * x + c(2) * y + c(3) * x * x + c(4) * x * y + c(5) * y * y);
    distance.push_back(std::abs(off));
    signed_distance.push_back(n.dot(mean - centroid.transpose()) >= 0 ? off : -off);
  }
  LaserAgreement agreement;
  if (distance.empty()) return agreement;
  std::sort(distance.begin(), distance.end());
  agreement.median_distance = distance[distance.size() / 2];
  agreement.p90_distance = distance[distance.size() * 9 / 10];
  std::nth_element(signed_distance.begin(), signed_distance.begin() + static_cast<std::ptrdiff_t>(signed_distance.size() / 2),
                   signed_distance.end());
  agreement.median_signed = signed_distance[signed_distance.size() / 2];
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
  const auto strided = [max_compared](const Eigen::MatrixX3d& cloud) {
    const Eigen::Index stride = std::max<Eigen::Index>(1, (cloud.rows() + max_compared - 1) / std::max<Eigen::Index>(max_compared, 1));
    Eigen::MatrixX3d sample((cloud.rows() + stride - 1) / stride, 3);
    for (Eigen::Index i = 0; i < sample.rows(); ++i) sample.row(i) = cloud.row(i * stride);
    return sample;
  };
  check.agreement = laser_agreement(strided(a), b, check.radius);
  const LaserAgreement back = laser_agreement(strided(b), a, check.radius);
  if (check.agreement.compared == 0 || back.compared == 0) {
    check.reason = "no point of one laser has enough of the other laser's stripes around it";
    return check;
  }
  check.checked = true;
  check.offset = 0.5 * (check.agreement.median_signed - back.median_signed);
  check.fit_bias = 0.5 * (check.agreement.median_signed + back.median_signed);
  check.resolution = std::max(check.limit, std::abs(check.fit_bias));
  check.agree = std::abs(check.offset) <= check.resolution;
  if (check.agree && check.resolution > check.limit) {  // an offset at the limit would not show: no verdict
    char text[300];
    std::snprintf(text, sizeof text,
                  "the lasers' stripes lie too far apart for the object's detail: their fitted surfaces differ by "
                  "%.3f both ways, above the limit %.3f (scan with more steps to check the lasers' agreement)",
                  check.fit_bias, check.limit);
    check.reason = text;
    check.checked = false;
  }
  return check;
}

nlohmann::json to_json(const LaserAgreementCheck& check) {
  nlohmann::json document = {{"checked", check.checked},
                             {"agree", check.agree},
                             {"offset", check.offset},
                             {"fit_bias", check.fit_bias},
                             {"resolution", check.resolution},
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
                "lasers 0 and 1 disagree: laser 0's cloud lies %.3f %s laser 1's (the median offset, measured both "
                "ways; limit %.3f) — two shifted copies of the object. A laser plane is off: recalibrate it "
                "(`scanstation calibrate laser --force`)",
                std::abs(check.offset), check.offset > 0 ? "outside" : "inside", check.resolution);
  return text;
}

}  // namespace scanstation::acquisition
