// A simulated turntable laser station for one object: the rig sized for the
// object (camera at the station's frame size, one light plane per laser of
// the station), the scene, and the hook that lets open_station's simulated
// camera render it in the state the simulated actuators set.
#pragma once

#include "drivers/station_description.h"
#include "sim/devices/scene_frame_source.h"
#include "sim/scan_objects.h"
#include "sim/turntable_rig.h"

#include <cstdint>
#include <memory>

namespace scanstation::sim {

struct SimulatedTurntable {
  ScanObject object;
  TurntableLaserRig rig;  // rig.lasers: one per laser of the station
  std::shared_ptr<const SceneRenderer> renderer;
  FrameSourceFactory frames;
};

inline constexpr double kSimulatedPlatterRadius = 60.0;

/// Throws InvalidInput for a station with no laser or more than two.
SimulatedTurntable simulated_turntable(ScanObject object, const drivers::StationDescription& station,
                                       std::uint64_t seed = 1);

}  // namespace scanstation::sim
