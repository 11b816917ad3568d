#include "sim/simulated_turntable.h"

#include "core/errors.h"
#include "sim/devices/sim_camera.h"

namespace scanstation::sim {

SimulatedTurntable simulated_turntable(ScanObject object, const drivers::StationDescription& station,
                                       std::uint64_t seed) {
  if (station.lasers.empty() || station.lasers.size() > 2)
    throw InvalidInput("simulated turntable: the rig has one or two lasers, the station names " +
                       std::to_string(station.lasers.size()));
  // The simulated camera streams the offered size nearest to the requested one.
  const drivers::FrameSize size =
      drivers::nearest_format(SimCameraConfig::default_formats(), station.camera.format).applied.size;
  const Eigen::MatrixX3d& P = object.on_platter.vertices.positions;
  const double height = P.col(2).maxCoeff();
  SimulatedTurntable sim;
  sim.rig = turntable_laser_rig(height, kSimulatedPlatterRadius, size.width, size.height);
  sim.rig.lasers.resize(station.lasers.size());
  sim.renderer = std::make_shared<const SceneRenderer>(
      turntable_scene(object.on_platter, sim.rig, kSimulatedPlatterRadius));
  sim.frames = scene_frame_source_factory(sim.renderer, sim.rig.camera, station, SensorModel{}, seed);
  sim.object = std::move(object);
  return sim;
}

}  // namespace scanstation::sim
