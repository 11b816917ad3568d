#include "acquisition/laser_plane_calibration.h"

#include "acquisition/laser_triangulation.h"
#include "core/errors.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>
#include <string>

namespace scanstation::acquisition {

std::vector<Eigen::Vector3d> laser_points_on_board(const LaserLine& line, const BoardPose& pose,
                                                   const PinholeCamera& camera, const LaserPlaneOptions& options) {
  const std::vector<cv::Point2f> outline =
      board_outline(pose, options.inner_corners, options.square_size, camera, -options.board_margin);
  std::vector<cv::Point2d> centres, normalised;
  for (const LinePeak& peak : line.peaks)
    if (cv::pointPolygonTest(outline, cv::Point2f(static_cast<float>(peak.x), static_cast<float>(peak.y)), false) > 0)
      centres.emplace_back(peak.x, peak.y);
  if (centres.empty()) return {};
  // The centres themselves are undistorted, not the image (as in the scan).
  cv::undistortPoints(centres, normalised, camera_matrix(camera), distortion_coefficients(camera), cv::noArray(),
                      cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-12));
  const Eigen::Vector3d n = pose.normal();
  const double offset = n.dot(pose.translation);  // board plane: n · x = offset (camera frame)
  std::vector<Eigen::Vector3d> points;
  for (const cv::Point2d& x : normalised) {
    const Eigen::Vector3d ray{x.x, x.y, 1.0};
    const double facing = n.dot(ray);
    if (std::abs(facing) < 1e-6) continue;  // a ray along the board: no intersection
    const double t = offset / facing;
    if (!(t > 0)) continue;
    // Near a square's edge the stripe's two flanks lie on different albedos
    // (black and white squares), which pulls its centre towards the white
    // side: such points are left out.
    const Eigen::Vector3d on_board = pose.rotation.transpose() * (t * ray - pose.translation);
    const auto near_edge = [&](double coordinate) {
      const double fraction = coordinate / options.square_size - std::floor(coordinate / options.square_size);
      return std::min(fraction, 1.0 - fraction) < options.edge_margin;
    };
    if (near_edge(on_board.x()) || near_edge(on_board.y())) continue;
    points.push_back(t * ray);
  }
  return points;
}

namespace {

struct PlaneFit {
  Eigen::Vector3d centroid, normal;
  double spread = 0;  // square root of the middle eigenvalue of the covariance
};

// Least squares: the normal is the eigenvector of the smallest eigenvalue of the covariance.
PlaneFit least_squares_plane(const std::vector<Eigen::Vector3d>& points, const std::vector<std::size_t>& subset) {
  PlaneFit fit;
  fit.centroid.setZero();
  for (const std::size_t i : subset) fit.centroid += points[i];
  fit.centroid /= static_cast<double>(subset.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const std::size_t i : subset) {
    const Eigen::Vector3d d = points[i] - fit.centroid;
    covariance += d * d.transpose();
  }
  covariance /= static_cast<double>(subset.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  fit.normal = solver.eigenvectors().col(0);
  fit.spread = std::sqrt(std::max(0.0, solver.eigenvalues()[1]));
  return fit;
}

std::vector<std::size_t> within(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                                const Eigen::Vector3d& normal, double distance) {
  std::vector<std::size_t> inliers;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (std::abs(normal.dot(points[i] - origin)) <= distance) inliers.push_back(i);
  return inliers;
}

}  // namespace

LaserPlaneCalibration fit_plane_robust(const std::vector<Eigen::Vector3d>& points, const LaserPlaneOptions& options) {
  if (points.size() < 3)
    throw InvalidInput("laser plane: " + std::to_string(points.size()) + " stripe points on the board; at least 3 are needed");
  if (!(options.inlier_distance > 0) || options.ransac_iterations < 1)
    throw InvalidInput("laser plane: the inlier distance and the RANSAC iterations must be positive");
  // RANSAC: the three-point plane with the most points within the band. The
  // engine is used raw (modulo), as std distributions differ between libraries.
  std::mt19937_64 engine(options.seed);
  const std::size_t n = points.size();
  std::vector<std::size_t> best;
  for (int trial = 0; trial < options.ransac_iterations; ++trial) {
    const std::size_t a = engine() % n, b = engine() % n, c = engine() % n;
    const Eigen::Vector3d normal = (points[b] - points[a]).cross(points[c] - points[a]);
    if (!(normal.norm() > 1e-12 * (points[b] - points[a]).squaredNorm())) continue;  // collinear sample
    std::vector<std::size_t> inliers = within(points, points[a], normal.normalized(), options.inlier_distance);
    if (inliers.size() > best.size()) best = std::move(inliers);
  }
  if (best.size() < 3) throw InvalidInput("laser plane: the stripe points lie on one line; they span no plane");
  // Refit on the inliers, re-select with the refined plane, refit once more.
  PlaneFit fit = least_squares_plane(points, best);
  for (int round = 0; round < 2; ++round) {
    const std::vector<std::size_t> inliers = within(points, fit.centroid, fit.normal, options.inlier_distance);
    if (inliers.size() < 3) break;
    best = inliers;
    fit = least_squares_plane(points, best);
  }
  // Stripes that coincide (the board never moved) fix a line, not a plane.
  if (fit.spread < 4.0 * options.inlier_distance)
    throw InvalidInput("laser plane: the stripes of all views lie nearly on one line (spread " +
                       std::to_string(fit.spread).substr(0, 5) +
                       " across it); move and tilt the board between views so the stripes cover the light plane");
  LaserPlaneCalibration result;
  result.plane = {fit.centroid, fit.normal};
  result.inliers = best.size();
  result.points = n;
  result.spread = fit.spread;
  double squared = 0;
  for (const std::size_t i : best) {
    const double d = std::abs(fit.normal.dot(points[i] - fit.centroid));
    squared += d * d;
    result.max = std::max(result.max, d);
  }
  result.rms = std::sqrt(squared / static_cast<double>(best.size()));
  return result;
}

LaserPlaneCalibration calibrate_laser_plane(const std::vector<LaserBoardView>& views, const PinholeCamera& camera,
                                            const LaserPlaneOptions& options) {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::size_t> per_view;
  std::size_t useful = 0;
  for (const LaserBoardView& view : views) {
    std::size_t found = 0;
    if (!view.corners.empty()) {
      const BoardPose pose = board_pose(view.corners, options.inner_corners, options.square_size, camera);
      const std::vector<Eigen::Vector3d> on_board =
          laser_points_on_board(extract_laser_line(view.laser_on, view.laser_off, options.line), pose, camera, options);
      points.insert(points.end(), on_board.begin(), on_board.end());
      found = on_board.size();
    }
    per_view.push_back(found);
    useful += found >= 3 ? 1 : 0;
  }
  if (useful < 2)
    throw InvalidInput("laser plane: the board and the laser stripe on it were found in " + std::to_string(useful) +
                       " of " + std::to_string(views.size()) + " views; at least 2 are needed");
  LaserPlaneCalibration result = fit_plane_robust(points, options);
  result.points_per_view = std::move(per_view);
  return result;
}

LaserPlane to_station_frame(const LaserPlane& plane, const PinholeCamera& camera) {
  return {camera.rotation.transpose() * (plane.origin - camera.translation), camera.rotation.transpose() * plane.normal};
}

LaserPlane to_camera_frame(const LaserPlane& plane, const PinholeCamera& camera) {
  return {camera.rotation * plane.origin + camera.translation, camera.rotation * plane.normal};
}

}  // namespace scanstation::acquisition
