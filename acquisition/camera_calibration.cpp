#include "acquisition/camera_calibration.h"

#include "core/errors.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <string>

namespace scanstation::acquisition {

std::optional<std::vector<cv::Point2f>> find_chessboard(const cv::Mat& image, cv::Size inner_corners) {
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(grey, inner_corners, corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
    return std::nullopt;
  cv::cornerSubPix(grey, corners, {11, 11}, {-1, -1},
                   cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01));
  return corners;
}

std::vector<cv::Point3f> chessboard_points(cv::Size inner_corners, double square_size) {
  std::vector<cv::Point3f> points;
  for (int r = 0; r < inner_corners.height; ++r)
    for (int c = 0; c < inner_corners.width; ++c)
      points.emplace_back(static_cast<float>(c * square_size), static_cast<float>(r * square_size), 0.0f);
  return points;
}

CameraIntrinsics calibrate_camera(const std::vector<std::vector<cv::Point2f>>& corners, cv::Size inner_corners,
                                  double square_size, cv::Size image_size, bool fix_k3) {
  if (corners.size() < 3)
    throw InvalidInput("camera calibration: " + std::to_string(corners.size()) + " chessboard views; at least 3 are needed");
  const std::vector<std::vector<cv::Point3f>> objects(corners.size(), chessboard_points(inner_corners, square_size));
  CameraIntrinsics camera;
  cv::Mat K, distortion, per_view;
  std::vector<cv::Mat> rvecs, tvecs;
  camera.rms = cv::calibrateCamera(objects, corners, image_size, K, distortion, rvecs, tvecs, cv::noArray(),
                                   cv::noArray(), per_view, fix_k3 ? cv::CALIB_FIX_K3 : 0);
  camera.camera_matrix = K;
  camera.distortion = distortion;
  camera.per_view_rms.assign(per_view.begin<double>(), per_view.end<double>());
  return camera;
}

}  // namespace scanstation::acquisition
