#include "acquisition/stereo_step_points.h"

#include "core/errors.h"

#include <numbers>
#include <opencv2/imgproc.hpp>

namespace scanstation::acquisition {

namespace {

// The matcher takes 8 bits: a 16-bit frame keeps its high byte.
cv::Mat eight_bit(const cv::Mat& frame, const char* which) {
  if (frame.empty()) return frame;
  if (frame.depth() == CV_8U && (frame.channels() == 1 || frame.channels() == 3)) return frame;
  if (frame.type() == CV_16UC1) {
    cv::Mat out;
    frame.convertTo(out, CV_8U, 1.0 / 256.0);
    return out;
  }
  throw InvalidInput(std::string("stereo step: the ") + which + " frame is not 8/16-bit grey or 8-bit BGR");
}

}  // namespace

StereoScanSetup stereo_scan_setup(const TurntableGeometry& geometry, const StereoScanParameters& parameters) {
  if (!geometry.right_camera)
    throw InvalidInput("stereo scan: the geometry (" + geometry.source + ") has no right camera");
  StereoScanSetup setup{stereo_station(geometry.camera, *geometry.right_camera), parameters.reconstruction};
  setup.options.matcher = fit_disparity_range(setup.station, parameters.volume_radius, parameters.volume_height,
                                              parameters.reconstruction.matcher);
  if (parameters.num_disparities > 0) setup.options.matcher.num_disparities = parameters.num_disparities;
  setup.options.maximum_radius = parameters.volume_radius;
  setup.options.maximum_height = parameters.volume_height;
  return setup;
}

LaserScanPoints stereo_step_points(const StereoStepFrames& frames, const StereoScanSetup& setup) {
  const double angle = frames.angle_deg * std::numbers::pi / 180.0;
  cv::Mat left = eight_bit(frames.left, "left"), right = eight_bit(frames.right, "right");
  // One frame of the pair saved in colour, the other grey (an image editor
  // rewrote one): the matcher needs one kind, so both go grey.
  if (left.channels() != right.channels()) {
    if (left.channels() == 3) cv::cvtColor(left, left, cv::COLOR_BGR2GRAY);
    if (right.channels() == 3) cv::cvtColor(right, right, cv::COLOR_BGR2GRAY);
  }
  return stereo_view_points(setup.station, left, right, angle, setup.options, eight_bit(frames.colour, "colour"));
}

}  // namespace scanstation::acquisition
