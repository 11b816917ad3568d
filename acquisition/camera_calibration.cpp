#include "acquisition/camera_calibration.h"

#include "core/errors.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace scanstation::acquisition {

std::optional<std::vector<cv::Point2f>> find_chessboard(const cv::Mat& image, cv::Size inner_corners) {
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(grey, inner_corners, corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
    return std::nullopt;
  // The refinement window must stay inside the squares around a corner: at
  // most 11 px (OpenCV's sample), less for a board seen small.
  double spacing = std::numeric_limits<double>::infinity();
  for (int r = 0; r < inner_corners.height; ++r)
    for (int c = 0; c + 1 < inner_corners.width; ++c) {
      const cv::Point2f d = corners[std::size_t(r * inner_corners.width + c + 1)] - corners[std::size_t(r * inner_corners.width + c)];
      spacing = std::min(spacing, std::sqrt(static_cast<double>(d.dot(d))));
    }
  const int half = std::clamp(static_cast<int>(0.4 * spacing), 2, 11);
  cv::cornerSubPix(grey, corners, {half, half}, {-1, -1},
                   cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01));
  // OpenCV may start at either end of the board; start at the top so that a
  // corner keeps its index while the board turns (turntable calibration).
  const cv::Point2f first = corners.front(), last = corners.back();
  if (first.y > last.y || (first.y == last.y && first.x > last.x)) std::reverse(corners.begin(), corners.end());
  return corners;
}

std::vector<cv::Point3f> chessboard_points(cv::Size inner_corners, double square_size) {
  std::vector<cv::Point3f> points;
  for (int r = 0; r < inner_corners.height; ++r)
    for (int c = 0; c < inner_corners.width; ++c)
      points.emplace_back(static_cast<float>(c * square_size), static_cast<float>(r * square_size), 0.0f);
  return points;
}

namespace {

constexpr double degree = std::numbers::pi / 180.0;

// The widest angle between the board planes of two views, from each view's
// homography (board → image) seen through a nominal camera: focal length the
// image's larger side, principal point at its centre. Boards turned alike
// have the same plane direction through any camera (the first two columns of
// K⁻¹H are the board's axes, scaled), so parallel boards are caught without
// the fit — which they leave free to trade the focal length against the
// distance, so that its rotations mean nothing: from one noise draw of
// parallel boards it returned a focal length of 49 000 px (the true one 400)
// with boards 135° apart and a focal uncertainty of 0.04%.
double widest_board_turn(const std::vector<std::vector<cv::Point2f>>& corners, const std::vector<cv::Point3f>& board,
                         cv::Size image_size) {
  std::vector<cv::Point2f> plane;
  for (const cv::Point3f& p : board) plane.emplace_back(p.x, p.y);
  const double f = std::max(image_size.width, image_size.height);
  const cv::Matx33d nominal_inverse(1 / f, 0, -0.5 * image_size.width / f, 0, 1 / f, -0.5 * image_size.height / f, 0, 0, 1);
  std::vector<cv::Vec3d> normals;
  for (const auto& view : corners) {
    const cv::Mat H = cv::findHomography(plane, view, 0);
    if (H.empty()) continue;
    const cv::Matx33d G = nominal_inverse * cv::Matx33d(H);
    const cv::Vec3d normal = cv::Vec3d(G(0, 0), G(1, 0), G(2, 0)).cross(cv::Vec3d(G(0, 1), G(1, 1), G(2, 1)));
    if (cv::norm(normal) > 0) normals.push_back(cv::normalize(normal));
  }
  double widest = 0;
  for (std::size_t i = 0; i < normals.size(); ++i)
    for (std::size_t j = i + 1; j < normals.size(); ++j)
      widest = std::max(widest, std::acos(std::clamp(normals[i].dot(normals[j]), -1.0, 1.0)));
  return widest;
}

std::string too_parallel(std::size_t views, double widest, const std::string& also) {
  return "camera calibration: the board is nearly parallel in all " + std::to_string(views) + " views (at most " +
         std::to_string(widest / degree).substr(0, 4) + " degrees apart" + also +
         "); tilt and turn it between views (by 10 degrees or more)";
}

}  // namespace

CameraIntrinsics calibrate_camera(const std::vector<std::vector<cv::Point2f>>& corners, cv::Size inner_corners,
                                  double square_size, cv::Size image_size, bool fix_k3) {
  if (corners.size() < 3)
    throw InvalidInput("camera calibration: " + std::to_string(corners.size()) + " chessboard views; at least 3 are needed");
  const std::vector<std::vector<cv::Point3f>> objects(corners.size(), chessboard_points(inner_corners, square_size));
  const double turn = widest_board_turn(corners, objects.front(), image_size);
  if (turn < 5.0 * degree) throw InvalidInput(too_parallel(corners.size(), turn, ""));
  CameraIntrinsics camera;
  cv::Mat K, distortion, per_view, deviations;
  std::vector<cv::Mat> rvecs, tvecs;
  camera.rms = cv::calibrateCamera(objects, corners, image_size, K, distortion, rvecs, tvecs, deviations,
                                   cv::noArray(), per_view, fix_k3 ? cv::CALIB_FIX_K3 : 0);
  camera.camera_matrix = K;
  camera.distortion = distortion;
  camera.per_view_rms.assign(per_view.begin<double>(), per_view.end<double>());
  // Board normals (third column of each rotation): Zhang's method needs the
  // board planes to differ, else the focal length trades off against the distance.
  double widest = 0;
  std::vector<cv::Vec3d> normals;
  for (const cv::Mat& rvec : rvecs) {
    cv::Matx33d R;
    cv::Rodrigues(rvec, R);
    normals.emplace_back(R(0, 2), R(1, 2), R(2, 2));
  }
  for (std::size_t i = 0; i < normals.size(); ++i)
    for (std::size_t j = i + 1; j < normals.size(); ++j)
      widest = std::max(widest, std::acos(std::clamp(normals[i].dot(normals[j]), -1.0, 1.0)));
  // The fit's own view of the same degeneracy (its board normals, its
  // uncertainty of fx), for boards turned just beyond the nominal test.
  const double fx_uncertainty = deviations.at<double>(0) / K.at<double>(0, 0);
  if (widest < 5.0 * degree || !(fx_uncertainty < 0.05))
    throw InvalidInput(too_parallel(corners.size(), widest,
                                    ", focal length ±" + std::to_string(100 * fx_uncertainty).substr(0, 4) + "%"));
  return camera;
}

PinholeCamera pinhole_camera(const CameraIntrinsics& intrinsics, cv::Size image_size) {
  PinholeCamera camera;
  camera.width = image_size.width;
  camera.height = image_size.height;
  camera.fx = intrinsics.camera_matrix(0, 0);
  camera.fy = intrinsics.camera_matrix(1, 1);
  camera.cx = intrinsics.camera_matrix(0, 2);
  camera.cy = intrinsics.camera_matrix(1, 2);
  const cv::Mat& d = intrinsics.distortion;
  const auto coefficient = [&](int i) { return static_cast<int>(d.total()) > i ? d.at<double>(i) : 0.0; };
  camera.distortion = {coefficient(0), coefficient(1), coefficient(4), coefficient(2), coefficient(3)};
  return camera;
}

}  // namespace scanstation::acquisition
