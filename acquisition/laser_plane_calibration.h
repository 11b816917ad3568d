// Laser plane calibration: the light plane of a line laser from its stripe on
// the calibration board at several poses. Each view's board pose comes from
// the chessboard (solvePnP with the calibrated camera); the stripe centres
// inside the board are undistorted and their camera rays cut with the board
// plane; a robust plane fit (RANSAC, then least squares on the inliers) over
// the points of all views gives the light plane.
#pragma once

#include "acquisition/board_pose.h"
#include "acquisition/laser_line.h"
#include "core/station_geometry.h"

#include <cstdint>
#include <vector>

namespace scanstation::acquisition {

/// One board pose seen with the laser off (corners, colour) and on (stripe).
/// corners  the chessboard corners found in laser_off (find_chessboard)
struct LaserBoardView {
  cv::Mat laser_off, laser_on;
  std::vector<cv::Point2f> corners;
};

/// inner_corners, square_size  the board (square size in the station's unit, e.g. mm)
/// line                 stripe extraction (acquisition/laser_line.h)
/// board_margin         stripe centres within the pattern shrunk by this many
///                      squares are used: the stripe blurs where it leaves the board
/// edge_margin          stripe centres closer than this many squares to a
///                      square's edge are left out (the albedo step biases them)
/// inlier_distance      RANSAC inlier band (station units) around a candidate plane
/// ransac_iterations, seed  RANSAC trials (deterministic: same seed, same plane)
struct LaserPlaneOptions {
  cv::Size inner_corners{9, 6};
  double square_size = 8.0;
  LaserLineOptions line;
  double board_margin = 0.25;
  double edge_margin = 0.1;
  double inlier_distance = 0.5;
  int ransac_iterations = 1000;
  std::uint64_t seed = 1;
};

/// plane          the light plane in the camera frame (origin: the centroid of the inliers)
/// rms, max       distances of the inliers to the plane (station units)
/// inliers, points  how many stripe points the fit kept, of how many
/// points_per_view  stripe points on the board in each view (0: none found)
/// spread         the smaller in-plane standard deviation of the inliers:
///                how far the stripes span the plane across their own direction
struct LaserPlaneCalibration {
  LaserPlane plane;
  double rms = 0, max = 0;
  std::size_t inliers = 0, points = 0;
  std::vector<std::size_t> points_per_view;
  double spread = 0;
};

/// The stripe points of one view in the camera frame: the peaks of `line`
/// inside the board (`pose`), undistorted, cut with the board plane.
std::vector<Eigen::Vector3d> laser_points_on_board(const LaserLine& line, const BoardPose& pose,
                                                   const PinholeCamera& camera, const LaserPlaneOptions& options);

/// A robust plane through `points`: RANSAC on three-point samples with
/// `inlier_distance`, then a least-squares refit (smallest principal axis) on
/// the inliers, twice. Throws InvalidInput for fewer than 3 points or points
/// that span no plane (all on a line: the stripes of every view coincide).
LaserPlaneCalibration fit_plane_robust(const std::vector<Eigen::Vector3d>& points, const LaserPlaneOptions& options);

/// The whole calibration from board views with a calibrated camera (pose not
/// used: the plane is in the camera frame). Throws InvalidInput when fewer
/// than 2 views show both the board and the stripe on it, or the stripes
/// span no plane.
LaserPlaneCalibration calibrate_laser_plane(const std::vector<LaserBoardView>& views, const PinholeCamera& camera,
                                            const LaserPlaneOptions& options = {});

/// A plane given in the camera frame of `camera`, expressed in the station
/// frame (camera.rotation, camera.translation: station → camera).
LaserPlane to_station_frame(const LaserPlane& camera_frame_plane, const PinholeCamera& camera);
/// The inverse: a station-frame plane in the camera frame.
LaserPlane to_camera_frame(const LaserPlane& station_plane, const PinholeCamera& camera);

}  // namespace scanstation::acquisition
