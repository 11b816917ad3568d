#include "acquisition/turntable_axis_calibration.h"

#include "acquisition/camera_calibration.h"
#include "core/errors.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace scanstation::acquisition {
namespace {

constexpr double degree = std::numbers::pi / 180.0;

std::string degrees(double radians) { return std::to_string(radians / degree).substr(0, 5) + " degrees"; }

// corners[i][k]: corner k of view i in the camera frame.
using CornerTracks = std::vector<std::vector<Eigen::Vector3d>>;

// The direction all corner displacements are perpendicular to: the smallest
// principal axis of the corners' scatter about their own means.
Eigen::Vector3d common_normal(const CornerTracks& corners) {
  const std::size_t views = corners.size(), count = corners.front().size();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < count; ++k) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < views; ++i) mean += corners[i][k];
    mean /= static_cast<double>(views);
    for (std::size_t i = 0; i < views; ++i) scatter += (corners[i][k] - mean) * (corners[i][k] - mean).transpose();
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(0);
}

// Signed turn of the board from the first view to view i about `axis`
// (the rotation vector of R_i R_0ᵀ projected on the axis).
double turn(const BoardPose& first, const BoardPose& pose, const Eigen::Vector3d& axis) {
  const Eigen::AngleAxisd relative(pose.rotation * first.rotation.transpose());
  return relative.angle() * relative.axis().dot(axis);
}

// Circles with a common centre in the plane ⊥ axis (basis u, v), one radius
// per corner: Kåsa's algebraic fit |q|² = 2 c·q + e_k, linear in c and e_k.
Eigen::Vector2d common_centre(const CornerTracks& corners, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const std::size_t views = corners.size(), count = corners.front().size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(views * count), static_cast<Eigen::Index>(2 + count));
  Eigen::VectorXd b(A.rows());
  for (std::size_t i = 0; i < views; ++i)
    for (std::size_t k = 0; k < count; ++k) {
      const Eigen::Index row = static_cast<Eigen::Index>(i * count + k);
      const Eigen::Vector2d q{u.dot(corners[i][k]), v.dot(corners[i][k])};
      A(row, 0) = 2 * q.x();
      A(row, 1) = 2 * q.y();
      A(row, static_cast<Eigen::Index>(2 + k)) = 1.0;
      b(row) = q.squaredNorm();
    }
  return A.colPivHouseholderQr().solve(b).head<2>();
}

}  // namespace

TurntableAxis calibrate_turntable_axis(const std::vector<BoardPose>& poses, const std::vector<double>& angles,
                                       cv::Size inner_corners, double square_size, double lowest_corner_height) {
  if (poses.size() != angles.size())
    throw InvalidInput("turntable axis: " + std::to_string(poses.size()) + " board poses but " +
                       std::to_string(angles.size()) + " turntable angles");
  if (poses.size() < 3)
    throw InvalidInput("turntable axis: the board was found at " + std::to_string(poses.size()) +
                       " turntable angles; at least 3 are needed");
  const auto [lowest, highest] = std::minmax_element(angles.begin(), angles.end());
  if (*highest - *lowest < 5 * degree)
    throw InvalidInput("turntable axis: the turntable angles span only " + degrees(*highest - *lowest) +
                       "; turn it over 5 degrees or more (30 or more for a precise axis)");
  CornerTracks corners;
  const std::vector<cv::Point3f> board = chessboard_points(inner_corners, square_size);
  for (const BoardPose& pose : poses) {
    corners.emplace_back();
    for (const cv::Point3f& p : board) corners.back().push_back(pose.to_camera({p.x, p.y, p.z}));
  }

  TurntableAxis axis;
  axis.direction = common_normal(corners);
  // Commanded angles grow counter-clockwise about +z: orient the axis so the
  // board's measured turns agree with them in sign.
  double agreement = 0, widest = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const double measured = turn(poses.front(), poses[i], axis.direction);
    agreement += measured * (angles[i] - angles.front());
    widest = std::max(widest, std::abs(measured));
  }
  if (widest < 2 * degree)
    throw InvalidInput("turntable axis: the board turned by at most " + degrees(widest) +
                       " between views; it must stand on the platter and turn with it");
  if (agreement < 0) axis.direction = -axis.direction;
  double angle_squared = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    axis.measured_angles.push_back(turn(poses.front(), poses[i], axis.direction));
    const double error = axis.measured_angles.back() - (angles[i] - angles.front());
    angle_squared += error * error;
  }
  axis.angle_rms = std::sqrt(angle_squared / static_cast<double>(poses.size()));

  const Eigen::Vector3d& a = axis.direction;
  const Eigen::Vector3d u = a.unitOrthogonal(), v = a.cross(u);
  const Eigen::Vector2d c = common_centre(corners, u, v);
  const Eigen::Vector3d centre = c.x() * u + c.y() * v;  // the axis point with a · x = 0
  // Each corner's circle: its height along the axis and its radius (means).
  double squared = 0, lowest_height = std::numeric_limits<double>::infinity();
  const std::size_t views = corners.size();
  for (std::size_t k = 0; k < corners.front().size(); ++k) {
    double height = 0, radius = 0;
    for (std::size_t i = 0; i < views; ++i) {
      height += a.dot(corners[i][k]);
      radius += (corners[i][k] - a.dot(corners[i][k]) * a - centre).norm();
    }
    height /= static_cast<double>(views);
    radius /= static_cast<double>(views);
    lowest_height = std::min(lowest_height, height);
    for (std::size_t i = 0; i < views; ++i) {
      const double along = a.dot(corners[i][k]) - height;
      const double across = (corners[i][k] - a.dot(corners[i][k]) * a - centre).norm() - radius;
      const double d2 = along * along + across * across;
      squared += d2;
      axis.max = std::max(axis.max, std::sqrt(d2));
    }
  }
  axis.rms = std::sqrt(squared / static_cast<double>(views * corners.front().size()));
  axis.origin = centre + (lowest_height - lowest_corner_height) * a;
  return axis;
}

PinholeCamera place_camera(const PinholeCamera& camera, const TurntableAxis& axis) {
  const Eigen::Vector3d z = axis.direction.normalized();
  // The camera centre is the camera frame's origin: from the platter origin to
  // it is −origin; its part across the axis points to the station's −y.
  const Eigen::Vector3d to_camera = -axis.origin;
  const Eigen::Vector3d across = to_camera - to_camera.dot(z) * z;
  if (!(across.norm() > 1e-9 * std::max(1.0, to_camera.norm())))
    throw InvalidInput("turntable axis: the camera lies on the turntable axis; the station frame is undefined");
  const Eigen::Vector3d y = -across.normalized();
  const Eigen::Vector3d x = y.cross(z);
  PinholeCamera placed = camera;
  placed.rotation.col(0) = x;
  placed.rotation.col(1) = y;
  placed.rotation.col(2) = z;
  placed.translation = axis.origin;
  return placed;
}

}  // namespace scanstation::acquisition
