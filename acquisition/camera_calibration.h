// Camera intrinsics and lens distortion from chessboard views (OpenCV), with
// per-view and overall reprojection RMS.
#pragma once

#include "core/station_geometry.h"

#include <opencv2/core.hpp>

#include <optional>
#include <vector>

namespace scanstation::acquisition {

/// Sub-pixel inner corners of a chessboard with `inner_corners` (columns ×
/// rows) in an 8-bit image, or nothing when the board is not found whole.
/// The first corner is the upper end of the board in the image.
std::optional<std::vector<cv::Point2f>> find_chessboard(const cv::Mat& image, cv::Size inner_corners);

/// The board's inner corners in its own plane (z = 0), row by row.
std::vector<cv::Point3f> chessboard_points(cv::Size inner_corners, double square_size);

/// One camera: K, distortion (k1, k2, p1, p2, k3), RMS reprojection error
/// over all corners and per view (pixels).
struct CameraIntrinsics {
  cv::Matx33d camera_matrix;
  cv::Mat distortion;
  double rms = 0;
  std::vector<double> per_view_rms;
};

/// corners  per view, the corners find_chessboard returned (≥ 3 views)
/// fix_k3   keep k3 = 0: for ordinary lenses k3 only trades off against k1, k2
///          (and through them the focal length) when the views do not reach
///          the image corners; free it for wide-angle lenses
/// Throws InvalidInput for fewer than 3 views, and for views whose boards are
/// all (nearly) parallel: within 5° of each other seen through a nominal
/// camera (from the homographies, before the fit) or as fitted, or fx
/// uncertain by more than 5%. Zhang's method cannot separate the focal
/// length from the distance then.
CameraIntrinsics calibrate_camera(const std::vector<std::vector<cv::Point2f>>& corners, cv::Size inner_corners,
                                  double square_size, cv::Size image_size, bool fix_k3 = true);

/// The calibrated camera as the station's camera model (pose: identity, i.e.
/// the camera frame, until the turntable calibration places it).
PinholeCamera pinhole_camera(const CameraIntrinsics& intrinsics, cv::Size image_size);

}  // namespace scanstation::acquisition
