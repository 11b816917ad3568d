// Stereo reconstruction of one turntable view: rectify the pair, match it
// densely (stereo_matcher.h), reproject every trusted disparity to 3D through
// the rectification's Q matrix, and turn the points into the object frame by
// the turntable angle, with a colour and a confidence per point.
#pragma once

#include "acquisition/laser_triangulation.h"
#include "acquisition/stereo_calibration.h"
#include "acquisition/stereo_matcher.h"
#include "core/station_geometry.h"

#include <opencv2/core.hpp>

#include <limits>
#include <utility>

namespace scanstation::acquisition {

/// A calibrated stereo pair on the station.
/// calibration      intrinsics, relative pose and rectification (r1, r2, p1, p2, q)
/// left_rotation, left_translation  the left camera's pose in the station
///                  frame: x_left = left_rotation · x_station + left_translation
/// *_map_x, *_map_y  rectification maps of each camera (cv::remap, CV_32F)
struct StereoStation {
  StereoCalibration calibration;
  Eigen::Matrix3d left_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d left_translation = Eigen::Vector3d::Zero();
  cv::Mat left_map_x, left_map_y, right_map_x, right_map_y;
};

/// A station from a stereo calibration (in station units) and the left
/// camera's pose; builds the rectification maps. Throws InvalidInput when
/// the calibration has no rectification.
StereoStation stereo_station(StereoCalibration calibration, const Eigen::Matrix3d& left_rotation,
                             const Eigen::Vector3d& left_translation);

/// A station from two known cameras (the simulator's truth, or any other
/// source of both poses): relative pose and cv::stereoRectify's
/// rectification (valid pixels only, as calibrate_stereo; but each view
/// keeps its own principal point, so converging cameras keep the object in
/// the middle of both rectified views instead of cropping it). Throws
/// InvalidInput for cameras of different image sizes.
StereoStation stereo_station(const PinholeCamera& left, const PinholeCamera& right);

/// left, right  8-bit frames of the two cameras (grey or BGR)
/// Returns the rectified pair: rows are epipolar lines, a point at left (x, y)
/// is at right (x − d, y). Throws InvalidInput for frames of another size
/// than the calibration's.
std::pair<cv::Mat, cv::Mat> rectify_pair(const StereoStation& station, const cv::Mat& left, const cv::Mat& right);

/// Fits the rectification to the working volume — the cylinder of `radius`
/// about the turntable axis from the platter up to `height` — so that its
/// disparities run from `margin` pixels upwards: the right rectified view
/// is shifted sideways (its principal point in p2, q's last entry and its
/// maps; rows stay epipolar, the reprojected points do not change). Returns
/// `base` with the disparity range covering the volume plus the margin: no
/// search outside it, nothing inside it missed, and the matcher's empty
/// left band (min + num disparities wide) as narrow as it can be.
/// Throws InvalidInput for a volume that reaches behind a camera.
StereoOptions fit_disparity_range(StereoStation& station, double radius, double height, StereoOptions base = {},
                                  double margin = 4.0);

/// The matcher's defaults without gap filling or median filter: only matched
/// pixels become points, for filled gaps invent geometry between the object
/// and what lies behind it.
StereoOptions reconstruction_matcher_options();

/// matcher          disparity options
/// minimum_height   points at or below this height over the platter are the
///                  platter itself: dropped (as for the laser)
/// maximum_radius, maximum_height  points outside this cylinder about the
///                  axis are background: dropped
/// discontinuity    pixels whose 3 × 3 neighbourhood spans a larger disparity
///                  range (pixels) lie on a depth edge, where block matching
///                  fattens the foreground: dropped; ≤ 0 keeps them
/// minimum_texture  pixels whose matching block has a smaller mean horizontal
///                  gradient (grey levels per pixel) were matched through the
///                  smoothness terms alone — a texture-less surface, or the
///                  dark background onto which SGBM spreads the foreground: dropped
/// texture_scale    mean horizontal gradient at which the texture part of
///                  the confidence is ½
/// pixel_step       reproject every n-th pixel of every n-th row only: a
///                  sampling as even as the turntable steps are apart, and
///                  as sparse as the reconstruction downstream can take
/// cell_mean        with pixel_step n > 1: each point from the mean (x, y, d)
///                  of the matched pixels within n/2 of its pixel whose
///                  disparity is within `discontinuity` of its own (one
///                  surface; all matched pixels when discontinuity ≤ 0)
///                  rather than from the pixel alone. A plane's disparity is
///                  affine in the rectified frame, so the mean lies on it;
///                  the matching noise averages down
struct StereoReconstructionOptions {
  StereoOptions matcher = reconstruction_matcher_options();
  double minimum_height = 0.5;
  double maximum_radius = std::numeric_limits<double>::infinity();
  double maximum_height = std::numeric_limits<double>::infinity();
  double discontinuity = 1.5;
  double minimum_texture = 2.0;
  double texture_scale = 6.0;
  int pixel_step = 1;
  bool cell_mean = false;
};

/// The points of a rectified disparity map (compute_disparity's convention:
/// CV_32F pixels, negative = none): each pixel (x, y, d) is reprojected by Q
/// (X, Y, Z, W)ᵀ = Q (x, y, d, 1)ᵀ into the rectified left camera, turned back
/// by r1ᵀ into the left camera, by the left camera pose into the station and
/// by the turntable angle into the object frame.
/// rectified_left   the rectified left frame (8-bit grey or BGR, same size):
///                  the texture of each point's block, and its colour
/// rectified_colour  if not empty, the colours come from this rectified left
///                  frame instead (e.g. taken with the projector off)
/// confidence       in (0, 1]: texture (g / (g + texture_scale), g the mean
///                  horizontal gradient over the block) times smoothness
///                  (exp(−(range / discontinuity)²), range the disparity span
///                  of the 3 × 3 neighbourhood)
/// Points are added to `points` in row-major pixel order.
void disparity_to_points(const StereoStation& station, const cv::Mat& disparity, const cv::Mat& rectified_left,
                         double turntable_angle, LaserScanPoints& points, const StereoReconstructionOptions& options = {},
                         const cv::Mat& rectified_colour = {});

/// One stereo view → points in the object frame: rectify_pair,
/// compute_disparity, disparity_to_points. The colours come from `colour`, a
/// left-camera frame without the projector's dots (8-bit grey or BGR), or
/// from `left` when it is empty.
LaserScanPoints stereo_view_points(const StereoStation& station, const cv::Mat& left, const cv::Mat& right,
                                   double turntable_angle, const StereoReconstructionOptions& options = {},
                                   const cv::Mat& colour = {});

}  // namespace scanstation::acquisition
