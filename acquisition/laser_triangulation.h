// Laser triangulation: stripe centres → 3D points in the object frame.
#pragma once

#include "acquisition/laser_line.h"
#include "core/point_cloud.h"
#include "core/station_geometry.h"

#include <limits>
#include <vector>

namespace scanstation::acquisition {

/// minimum_height   points at or below this height over the platter are the
///                  platter itself (station units): dropped
/// maximum_radius   points farther from the turntable axis are background: dropped
/// minimum_incidence  rays meeting the light plane at a smaller |cos| are
///                  too grazing to triangulate stably: dropped
struct LaserTriangulationOptions {
  double minimum_height = 0.5;
  double maximum_radius = std::numeric_limits<double>::infinity();
  double minimum_incidence = 0.05;
};

/// Points of a scan in the object frame with their colour (from the laser-off
/// frame) and the confidence of the stripe centre they came from.
struct LaserScanPoints {
  PointCloud cloud;
  std::vector<double> confidence;
};

/// Adds the points of one stripe to `points`: each sub-pixel centre is
/// undistorted (cv::undistortPoints on the centres, not on the image), its
/// camera ray is cut with the light plane, and the station point is turned
/// back by the turntable angle into the object frame. `laser_off` (8-bit grey
/// or BGR) gives the colour.
void triangulate_laser_line(const LaserLine& line, const PinholeCamera& camera, const LaserPlane& plane,
                            double turntable_angle, const cv::Mat& laser_off, LaserScanPoints& points,
                            const LaserTriangulationOptions& options = {});

/// OpenCV's camera matrix and distortion vector (k1, k2, p1, p2, k3) of a camera.
cv::Matx33d camera_matrix(const PinholeCamera& camera);
cv::Vec<double, 5> distortion_coefficients(const PinholeCamera& camera);

}  // namespace scanstation::acquisition
