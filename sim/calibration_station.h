// The simulated station a calibration is captured from: the station's rig
// (station_rig, the one `scan --backend sim` scans with; or its stereo rig,
// station_stereo_rig, the one `scan --rig stereo` scans with) with only the
// chessboard on its platter, its devices opened as a scan opens them — the
// camera serves renders of the board in the state the simulated stepper and
// laser lines set (sim/devices/scene_frame_source.h) — and the simulator's
// operator, who puts the board in its next place between views. The capture
// itself drives the devices (acquisition/calibration_capture.h).
#pragma once

#include "drivers/station_description.h"
#include "sim/calibration_views.h"
#include "sim/devices/open_station.h"
#include "sim/devices/scene_frame_source.h"
#include "sim/stereo_rig.h"
#include "sim/turntable_rig.h"

#include <cstdint>
#include <memory>

namespace scanstation::sim {

class CalibrationStation {
 public:
  /// Opens every role of `station` (simulated) under a GuardedStation (one
  /// per process). Frames average `supersampling`² rays per pixel
  /// (sim/supersampling.h); sensor noise from `seed`. Until the first
  /// place() the board stands upright at the axis.
  CalibrationStation(const drivers::StationDescription& station, const TurntableLaserRig& rig, std::uint64_t seed,
                     int supersampling = 2);
  /// The stereo rig's: both cameras (the right one with its own noise seed)
  /// and the turntable, the projector dark (no dots on the board).
  CalibrationStation(const drivers::StationDescription& station, const StereoRig& rig, std::uint64_t seed,
                     int supersampling = 2);

  OpenStation& devices() { return *station_; }

  /// The operator: from now on (the station's clock) the board of
  /// `placement` stands on the platter, turned on it so that the camera sees
  /// it as at placement.angle wherever the table stands — a person turns the
  /// board, not the table.
  void place(const BoardPlacement& placement);

 private:
  CalibrationStation(const drivers::StationDescription& station, Scene base, const PinholeCamera& left,
                     const PinholeCamera* right, std::uint64_t seed, int supersampling);

  drivers::StationDescription description_;
  Scene base_;  // platter and lasers, no object
  std::shared_ptr<SceneStage> stage_;
  GuardedStation station_;
  VirtualActuators actuators_;
};

}  // namespace scanstation::sim
