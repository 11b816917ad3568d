#include "sim/simulated_turntable.h"

#include "core/errors.h"
#include "sim/devices/sim_camera.h"

namespace scanstation::sim {

TurntableLaserRig station_rig(const drivers::StationDescription& station) {
  if (station.lasers.empty() || station.lasers.size() > 2)
    throw InvalidInput("simulated turntable: the rig has one or two lasers, the station names " +
                       std::to_string(station.lasers.size()));
  // The simulated camera streams the offered size nearest to the requested one.
  const drivers::FrameSize size =
      drivers::nearest_format(SimCameraConfig::default_formats(), station.camera.format).applied.size;
  TurntableLaserRig rig = turntable_laser_rig(kSimulatedRigHeight, kSimulatedPlatterRadius, size.width, size.height);
  rig.lasers.resize(station.lasers.size());
  return rig;
}

std::vector<LaserPlane> light_planes(const TurntableLaserRig& rig) {
  std::vector<LaserPlane> planes;
  for (const LineLaser& laser : rig.lasers) planes.push_back(laser.plane);
  return planes;
}

SimulatedTurntable simulated_turntable(ScanObject object, const drivers::StationDescription& station,
                                       std::uint64_t seed) {
  const double height = object.on_platter.vertices.positions.col(2).maxCoeff();
  // A small tolerance: scan_object scales to the height in floating point.
  if (height > kSimulatedRigHeight * (1 + 1e-9))
    throw InvalidInput("simulated turntable: '" + object.name + "' stands " + std::to_string(height) +
                       " high; the rig frames objects up to " + std::to_string(kSimulatedRigHeight));
  SimulatedTurntable sim;
  sim.rig = station_rig(station);
  sim.renderer = std::make_shared<const SceneRenderer>(
      turntable_scene(object.on_platter, sim.rig, kSimulatedPlatterRadius));
  sim.frames = scene_frame_source_factory(sim.renderer, sim.rig.camera, station, SensorModel{}, seed);
  sim.object = std::move(object);
  return sim;
}

}  // namespace scanstation::sim
