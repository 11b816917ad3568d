// Stereo calibration from chessboard views (OpenCV): each camera's
// intrinsics and distortion, the pose of the right camera relative to the
// left, and the rectification, with per-view and overall reprojection RMS.
#pragma once

#include "acquisition/camera_calibration.h"

#include <opencv2/core.hpp>

#include <optional>
#include <string>
#include <vector>

namespace scanstation::acquisition {

/// Which model and flags the joint stereo refinement uses.
/// standard       each camera calibrated alone (k1, k2, p1, p2, k3), then every
///                parameter refined jointly with the stereo pose
/// opencv_sample  the flags of OpenCV's stereo_calib sample (same focal length,
///                fixed aspect ratio, zero tangential distortion, rational
///                model with k3..k5 fixed): the reference
enum class StereoModel { standard, opencv_sample };

/// left, right     the two cameras after the joint refinement
/// rotation, translation  right camera pose: x_right = R x_left + T (board squares as unit)
/// rms             joint RMS over both images of every used pair
/// per_view_rms    one row per used pair: left and right RMS
/// used_views      indices of the input pairs where the board was found in both
/// r1, r2, p1, p2, q  cv::stereoRectify's rectification (alpha = 0: valid pixels only)
struct StereoCalibration {
  CameraIntrinsics left, right;
  cv::Matx33d rotation;
  cv::Vec3d translation;
  double rms = 0;
  std::vector<cv::Vec2d> per_view_rms;
  std::vector<std::size_t> used_views;
  cv::Size image_size;
  cv::Mat r1, r2, p1, p2, q;
};

/// left_images, right_images  pairs of 8-bit views of the same chessboard
/// inner_corners  e.g. 9 × 6; square_size  in the unit wanted for translation
/// Throws InvalidInput when fewer than 3 pairs show the whole board in both
/// images, or the images differ in size.
StereoCalibration calibrate_stereo(const std::vector<cv::Mat>& left_images, const std::vector<cv::Mat>& right_images,
                                   cv::Size inner_corners, double square_size, StereoModel model = StereoModel::standard);

}  // namespace scanstation::acquisition
