#include "acquisition/turntable_step_points.h"

#include "core/errors.h"

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

namespace scanstation::acquisition {

cv::Mat grey8(const cv::Mat& frame) {
  cv::Mat grey;
  if (frame.type() == CV_8UC1) return frame;
  if (frame.type() == CV_16UC1) {
    frame.convertTo(grey, CV_8U, 1.0 / 257.0);
    return grey;
  }
  if (frame.type() == CV_8UC3) {
    cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
    return grey;
  }
  throw InvalidInput("camera frames must be 8-bit or 16-bit grey or 8-bit BGR");
}

std::vector<LaserScanPoints> step_points(const StepFrames& frames, const TurntableGeometry& geometry,
                                         const LaserScanParameters& parameters) {
  const PinholeCamera& camera = geometry.camera;
  const auto check_size = [&](const cv::Mat& frame) {
    if (frame.cols != camera.width || frame.rows != camera.height)
      throw InvalidInput("laser scan: a " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                         " frame does not fit the " + std::to_string(camera.width) + "x" +
                         std::to_string(camera.height) + " camera of the geometry");
  };
  check_size(frames.off);
  const cv::Mat off = grey8(frames.off);
  // Colour from the laser-off frame as captured (BGR keeps its colour).
  const cv::Mat colour = frames.off.type() == CV_16UC1 ? off : frames.off;
  const double angle = frames.angle_deg * std::numbers::pi / 180.0;
  std::vector<LaserScanPoints> clouds(geometry.lasers.size());
  for (const auto& [laser, frame] : frames.on) {
    if (laser < 0 || static_cast<std::size_t>(laser) >= geometry.lasers.size())
      throw InvalidInput("laser scan: laser " + std::to_string(laser) + " has no plane in the geometry (" +
                         std::to_string(geometry.lasers.size()) + " lasers)");
    check_size(frame);
    LaserLine line = extract_laser_line(grey8(frame), off, parameters.line);
    if (parameters.row_step > 1) {
      const bool by_row = parameters.line.stripe == StripeDirection::vertical;
      std::erase_if(line.peaks, [&](const LinePeak& p) {
        return static_cast<int>(std::lround(by_row ? p.y : p.x)) % parameters.row_step != 0;
      });
    }
    triangulate_laser_line(line, camera, geometry.lasers[static_cast<std::size_t>(laser)], angle, colour,
                           clouds[static_cast<std::size_t>(laser)], parameters.triangulation);
  }
  return clouds;
}

void append_points(LaserScanPoints& to, const LaserScanPoints& from) {
  PointCloud& cloud = to.cloud;
  const Eigen::Index old = cloud.size(), added = from.cloud.size();
  if (added == 0) return;
  cloud.positions.conservativeResize(old + added, 3);
  cloud.positions.bottomRows(added) = from.cloud.positions;
  cloud.colors.conservativeResize(old + added, 3);
  cloud.colors.bottomRows(added) = from.cloud.colors;
  to.confidence.insert(to.confidence.end(), from.confidence.begin(), from.confidence.end());
}

}  // namespace scanstation::acquisition
