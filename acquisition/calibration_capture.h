// Taking the calibration views from a station's devices, over the driver
// interfaces only (drivers/): the same code captures from a real station and
// from the simulated one (sim/devices/), as scan_turntable does for a scan.
// Between placements the operator moves the board (PlaceBoard: a prompt on a
// real station; on the simulator, sim::place_board). The table angles of the
// axis calibration and the lasers of the plane calibration are commanded
// through the devices, and every frame passes the frame gate
// (drivers/frame_gate.h): its exposure began after the board was placed, the
// table settled and the laser switched.
#pragma once

#include "acquisition/stereo_scan.h"
#include "acquisition/turntable_scan.h"
#include "core/progress.h"

#include <functional>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace scanstation::acquisition {

/// Puts the board in its place for placement `index` of `count` and returns
/// once it stands still.
using PlaceBoard = std::function<void(int index, int count)>;

/// off        the laser-off frame, 8-bit grey (grey8)
/// on         laser i lit alone at index i (laser views), 8-bit grey
/// angle_deg  the table's angle (Turntable::angle(), exact in motor steps)
struct CalibrationView {
  cv::Mat off;
  std::vector<cv::Mat> on;
  double angle_deg = 0;
};

/// `count` placements of the board, the table still (camera intrinsics,
/// laser planes): for each, place(i, count), then the laser-off frame and,
/// with `lasers`, one frame per laser of `devices` lit alone. The camera
/// streams for the duration. Device errors propagate.
std::vector<CalibrationView> capture_board_views(TurntableScanDevices& devices, int count, const PlaceBoard& place,
                                                 bool lasers, const ProgressCallback& progress = {});

/// One placement of the board seen by both cameras of a stereo rig.
/// left, right  8-bit grey frames (grey8) exposed after the placement
struct StereoCalibrationView {
  cv::Mat left, right;
  double angle_deg = 0;
};

/// `count` placements of the board, the table still (stereo pair): for each,
/// place(i, count), then a frame from each camera; the projector, if any,
/// stays off (its dots would hide the board's corners). Both cameras stream
/// for the duration. Device errors propagate.
std::vector<StereoCalibrationView> capture_stereo_board_views(StereoScanDevices& devices, int count,
                                                              const PlaceBoard& place,
                                                              const ProgressCallback& progress = {});

/// One placement of the board seen at the table angles `angles_deg`
/// (absolute, Turntable::rotate_to; turntable axis): place(0, 1), then for
/// each angle the table turned there and the laser-off frame. The table is
/// turned back to its angle at the call.
std::vector<CalibrationView> capture_turntable_views(TurntableScanDevices& devices,
                                                     const std::vector<double>& angles_deg, const PlaceBoard& place,
                                                     const ProgressCallback& progress = {});

}  // namespace scanstation::acquisition
