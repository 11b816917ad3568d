#include "acquisition/calibration_capture.h"

#include "acquisition/turntable_step_points.h"
#include "core/errors.h"

namespace scanstation::acquisition {

namespace {

CalibrationView view_of(const std::vector<CapturedFrame>& frames, double angle_deg) {
  CalibrationView view;
  view.angle_deg = angle_deg;
  for (const CapturedFrame& f : frames)
    (f.laser ? view.on.emplace_back() : view.off) = grey8(f.frame.image).clone();
  return view;
}

}  // namespace

std::vector<CalibrationView> capture_board_views(TurntableScanDevices& devices, int count, const PlaceBoard& place,
                                                 bool lasers, const ProgressCallback& progress) {
  if (count < 1) throw InvalidInput("calibration capture: at least one board placement");
  const StreamingCamera streaming(devices.camera);
  std::vector<CalibrationView> views;
  for (int i = 0; i < count; ++i) {
    place(i, count);
    views.push_back(view_of(capture_laser_frames(devices, devices.clock.now(), lasers), devices.turntable.angle()));
    if (progress) progress(double(i + 1) / count);
  }
  return views;
}

std::vector<StereoCalibrationView> capture_stereo_board_views(StereoScanDevices& devices, int count,
                                                              const PlaceBoard& place,
                                                              const ProgressCallback& progress) {
  if (count < 1) throw InvalidInput("calibration capture: at least one board placement");
  const StreamingCamera left(devices.left), right(devices.right);
  drivers::Timestamp dark = devices.clock.now();
  if (devices.projector) dark = devices.projector->set(false);
  std::vector<StereoCalibrationView> views;
  for (int i = 0; i < count; ++i) {
    place(i, count);
    const drivers::Timestamp placed = std::max(dark, devices.clock.now());
    StereoCalibrationView view;
    view.left = grey8(grab_frame(devices.left, devices.clock, placed, devices.timeout).frame.image).clone();
    view.right = grey8(grab_frame(devices.right, devices.clock, placed, devices.timeout).frame.image).clone();
    view.angle_deg = devices.turntable.angle();
    views.push_back(std::move(view));
    if (progress) progress(double(i + 1) / count);
  }
  return views;
}

std::vector<CalibrationView> capture_turntable_views(TurntableScanDevices& devices,
                                                     const std::vector<double>& angles_deg, const PlaceBoard& place,
                                                     const ProgressCallback& progress) {
  if (angles_deg.empty()) throw InvalidInput("calibration capture: at least one turntable angle");
  const double start = devices.turntable.angle();
  const StreamingCamera streaming(devices.camera);
  place(0, 1);
  const drivers::Timestamp placed = devices.clock.now();
  std::vector<CalibrationView> views;
  for (const double angle : angles_deg) {
    const drivers::Timestamp settled = std::max(placed, devices.turntable.rotate_to(angle));
    views.push_back(view_of(capture_laser_frames(devices, settled, false), devices.turntable.angle()));
    if (progress) progress(double(views.size()) / double(angles_deg.size()));
  }
  devices.turntable.rotate_to(start);
  return views;
}

}  // namespace scanstation::acquisition
