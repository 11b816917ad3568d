// The points of one turntable step: every laser-on frame against the step's
// laser-off frame, triangulated with that laser's plane, turned into the
// object frame by the step's angle. The same function serves the live scan
// and the replay of a session, so both give the same points.
#pragma once

#include "acquisition/laser_scan_parameters.h"
#include "acquisition/turntable_geometry.h"

#include <opencv2/core.hpp>
#include <utility>
#include <vector>

namespace scanstation::acquisition {

/// angle_deg  turntable angle of the step (degrees, as Turntable::angle())
/// off        the laser-off frame
/// on         (laser index, laser-on frame) pairs
/// Frames are 8-bit or 16-bit grey, or 8-bit BGR.
struct StepFrames {
  double angle_deg = 0;
  cv::Mat off;
  std::vector<std::pair<int, cv::Mat>> on;
};

/// One cloud per laser of `geometry` (empty for a laser without a frame).
/// Throws InvalidInput for a frame of another size than the camera, of an
/// unsupported type, or a laser index the geometry has no plane for.
std::vector<LaserScanPoints> step_points(const StepFrames& frames, const TurntableGeometry& geometry,
                                         const LaserScanParameters& parameters);

/// The 8-bit grey image of a camera frame (16-bit grey scaled by 1/257, the
/// inverse of how Y16 widens 8-bit levels; BGR converted). Throws
/// InvalidInput for other types.
cv::Mat grey8(const cv::Mat& frame);

/// Appends `from` to `to` (positions, colours, confidences).
void append_points(LaserScanPoints& to, const LaserScanPoints& from);

}  // namespace scanstation::acquisition
