#include "sim/simulated_stereo.h"

#include "core/errors.h"
#include "sim/devices/sim_camera.h"
#include "sim/simulated_turntable.h"

namespace scanstation::sim {

namespace {

std::string station_name(const drivers::StationDescription& station) {
  return station.source.empty() ? "the station '" + station.name + "'" : station.source.string();
}

// The size a simulated camera streams for the requested format (the nearest offered).
drivers::FrameSize streamed_size(const drivers::CameraRole& camera) {
  return drivers::nearest_format(SimCameraConfig::default_formats(), camera.format).applied.size;
}

}  // namespace

StereoRig station_stereo_rig(const drivers::StationDescription& station) {
  if (!station.right_camera)
    throw InvalidInput(station_name(station) +
                       ": no [right_camera]: a stereo rig needs a second camera (same keys as [camera])");
  const drivers::FrameSize left = streamed_size(station.camera), right = streamed_size(*station.right_camera);
  if (left.width != right.width || left.height != right.height)
    throw InvalidInput(station_name(station) + ": right_camera streams " + std::to_string(right.width) + "x" +
                       std::to_string(right.height) + ", camera " + std::to_string(left.width) + "x" +
                       std::to_string(left.height) + ": a stereo rig needs two cameras of the same size");
  return stereo_rig(kSimulatedRigHeight, kSimulatedPlatterRadius, left.width, left.height);
}

SimulatedStereo simulated_stereo(ScanObject object, const drivers::StationDescription& station, std::uint64_t seed) {
  check_fits_rig(object);
  SimulatedStereo sim;
  sim.rig = station_stereo_rig(station);
  sim.renderer = std::make_shared<const SceneRenderer>(stereo_scene(object.on_platter, sim.rig, kSimulatedPlatterRadius));
  sim.left_frames = scene_frame_source_factory(sim.renderer, sim.rig.left, station, SensorModel{}, seed);
  // Two sensors, two noise streams.
  sim.right_frames = scene_frame_source_factory(sim.renderer, sim.rig.right, station, SensorModel{}, ~seed);
  sim.object = std::move(object);
  return sim;
}

}  // namespace scanstation::sim
