// A simulated turntable laser station: one fixed rig per station description
// (camera at the station's frame size, one light plane per laser of the
// station, framed for objects up to kSimulatedRigHeight on a platter of
// kSimulatedPlatterRadius) — the same rig whatever the object, so that one
// calibration of the station (scanstation calibrate --backend sim) applies to
// every object scanned on it. The object is placed and scaled to fit the rig
// (sim/scan_objects.h), the scene built, and the hook made that lets
// open_station's simulated camera render it in the state the simulated
// actuators set.
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

/// The station's simulated rig: turntable_laser_rig(kSimulatedRigHeight,
/// kSimulatedPlatterRadius) at the frame size the simulated camera streams for
/// the station's requested format, one laser per laser of the station.
/// Throws InvalidInput for a station with no laser or more than two.
TurntableLaserRig station_rig(const drivers::StationDescription& station);

/// The rig's true light planes, laser i at index i (with rig.camera, the
/// simulator's truth: acquisition::simulator_truth turns them into the
/// geometry a scan triangulates with; sim stops at the driver interfaces).
std::vector<LaserPlane> light_planes(const TurntableLaserRig& rig);

/// The station's rig (station_rig) with `object` on its platter; the object
/// must fit the rig (scan_object places built-ins and mesh files so).
/// Throws InvalidInput for a station with no laser or more than two, or an
/// object taller than the rig frames.
SimulatedTurntable simulated_turntable(ScanObject object, const drivers::StationDescription& station,
                                       std::uint64_t seed = 1);

}  // namespace scanstation::sim
