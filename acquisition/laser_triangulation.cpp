#include "acquisition/laser_triangulation.h"

#include "core/errors.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace scanstation::acquisition {

cv::Matx33d camera_matrix(const PinholeCamera& camera) {
  return {camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1};
}

cv::Vec<double, 5> distortion_coefficients(const PinholeCamera& camera) {
  const BrownConrady& d = camera.distortion;
  return {d.k1, d.k2, d.p1, d.p2, d.k3};
}

namespace {

std::array<std::uint8_t, 3> colour_at(const cv::Mat& image, double x, double y) {
  cv::Mat patch;
  cv::getRectSubPix(image, {1, 1}, cv::Point2f(static_cast<float>(x), static_cast<float>(y)), patch);
  if (patch.channels() == 1) {
    const std::uint8_t g = patch.at<std::uint8_t>(0, 0);
    return {g, g, g};
  }
  const cv::Vec3b bgr = patch.at<cv::Vec3b>(0, 0);
  return {bgr[2], bgr[1], bgr[0]};
}

}  // namespace

void triangulate_laser_line(const LaserLine& line, const PinholeCamera& camera, const LaserPlane& plane,
                            double turntable_angle, const cv::Mat& laser_off, LaserScanPoints& points,
                            const LaserTriangulationOptions& options) {
  if (line.peaks.empty()) return;
  if (laser_off.depth() != CV_8U || (laser_off.channels() != 1 && laser_off.channels() != 3))
    throw InvalidInput("laser triangulation: the laser-off frame must be 8-bit grey or BGR");
  std::vector<cv::Point2d> centres, normalised;
  centres.reserve(line.peaks.size());
  for (const LinePeak& peak : line.peaks) centres.emplace_back(peak.x, peak.y);
  // Iterated to convergence: OpenCV's default 5 iterations leave ~1e-3 px at
  // the image corners with a real lens.
  cv::undistortPoints(centres, normalised, camera_matrix(camera), distortion_coefficients(camera), cv::noArray(),
                      cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-12));

  const Eigen::Vector3d eye = camera.centre();
  const Eigen::Matrix3d to_object = turntable_rotation(turntable_angle).transpose();
  std::vector<Eigen::Vector3d> found;
  std::vector<std::array<std::uint8_t, 3>> colours;
  std::vector<double> confidence;
  for (std::size_t i = 0; i < normalised.size(); ++i) {
    const Eigen::Vector3d ray = (camera.rotation.transpose() * Eigen::Vector3d(normalised[i].x, normalised[i].y, 1.0)).normalized();
    const double incidence = plane.normal.dot(ray);
    if (std::abs(incidence) < options.minimum_incidence) continue;
    const double t = plane.normal.dot(plane.origin - eye) / incidence;  // ray–plane intersection
    if (!(t > 0)) continue;
    const Eigen::Vector3d station = eye + t * ray;
    if (station.z() <= options.minimum_height || station.head<2>().norm() > options.maximum_radius) continue;
    found.push_back(to_object * station);
    colours.push_back(colour_at(laser_off, centres[i].x, centres[i].y));
    confidence.push_back(line.peaks[i].confidence);
  }

  PointCloud& cloud = points.cloud;
  const Eigen::Index old = cloud.size(), added = static_cast<Eigen::Index>(found.size());
  cloud.positions.conservativeResize(old + added, 3);
  cloud.colors.conservativeResize(old + added, 3);
  for (Eigen::Index i = 0; i < added; ++i) {
    cloud.positions.row(old + i) = found[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) cloud.colors(old + i, k) = colours[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
  }
  points.confidence.insert(points.confidence.end(), confidence.begin(), confidence.end());
}

}  // namespace scanstation::acquisition
