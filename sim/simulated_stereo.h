// A simulated stereo station: the sim stereo rig (sim/stereo_rig.h) framed
// for the same working volume as the simulated turntable station (objects up
// to kSimulatedRigHeight, within kSimulatedObjectRadius of the axis, on a
// platter of kSimulatedPlatterRadius), fixed per station description so that
// its geometry does not depend on the object; the object placed on the
// platter, and one frame source per camera for open_station's simulated
// cameras, rendering the scene as the simulated stepper turned it and with
// the dots while the projector's output is high.
#pragma once

#include "drivers/station_description.h"
#include "sim/devices/scene_frame_source.h"
#include "sim/scan_objects.h"
#include "sim/stereo_rig.h"

#include <cstdint>
#include <memory>

namespace scanstation::sim {

struct SimulatedStereo {
  ScanObject object;
  StereoRig rig;
  std::shared_ptr<const SceneRenderer> renderer;
  FrameSourceFactory left_frames, right_frames;
};

/// The station's stereo rig at the frame size its simulated cameras stream.
/// Throws InvalidInput naming the station when it has no right camera, or
/// when the two cameras stream different sizes.
StereoRig station_stereo_rig(const drivers::StationDescription& station);

/// The station's stereo rig with `object` on the platter; the right camera's
/// sensor noise has its own seed. Throws as station_stereo_rig, and for an
/// object taller than the rig frames.
SimulatedStereo simulated_stereo(ScanObject object, const drivers::StationDescription& station,
                                 std::uint64_t seed = 1);

}  // namespace scanstation::sim
