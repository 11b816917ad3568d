#include "sim/calibration_station.h"

#include "sim/simulated_turntable.h"

namespace scanstation::sim {

namespace {

Scene with_board(Scene scene, const ChessboardTarget& board) {
  scene.board = board;
  return scene;
}

}  // namespace

CalibrationStation::CalibrationStation(const drivers::StationDescription& station, Scene base,
                                       const PinholeCamera& left, const PinholeCamera* right, std::uint64_t seed,
                                       int supersampling)
    : description_(station),
      base_(std::move(base)),
      stage_(std::make_shared<SceneStage>(std::make_shared<const SceneRenderer>(with_board(base_, {})))),
      station_(description_, camera_role | turntable_role | (right ? right_camera_role : laser_role),
               scene_frame_source_factory(stage_, left, description_, {}, seed, supersampling),
               drivers::OnSignal::end_process,
               // Two sensors, two noise streams (as sim/simulated_stereo.h).
               right ? scene_frame_source_factory(stage_, *right, description_, {}, ~seed, supersampling)
                     : FrameSourceFactory{}),
      actuators_(virtual_actuators(*station_, description_)) {}

CalibrationStation::CalibrationStation(const drivers::StationDescription& station, const TurntableLaserRig& rig,
                                       std::uint64_t seed, int supersampling)
    : CalibrationStation(station, turntable_scene({}, rig, kSimulatedPlatterRadius), rig.camera, nullptr, seed,
                         supersampling) {}

CalibrationStation::CalibrationStation(const drivers::StationDescription& station, const StereoRig& rig,
                                       std::uint64_t seed, int supersampling)
    : CalibrationStation(station, stereo_scene({}, rig, kSimulatedPlatterRadius, false), rig.left, &rig.right, seed,
                         supersampling) {}

void CalibrationStation::place(const BoardPlacement& placement) {
  const drivers::Timestamp now = station_->clock->now();
  // The platter stands at its physical angle; the board goes on it turned by
  // the difference, so that the world sees it at placement.angle.
  const Eigen::Matrix3d turn = turntable_rotation(placement.angle - actuators_.angle(now));
  ChessboardTarget board = placement.board;
  board.origin = turn * board.origin;
  board.across = turn * board.across;
  board.down = turn * board.down;
  stage_->change(std::make_shared<const SceneRenderer>(with_board(base_, board)), now);
}

}  // namespace scanstation::sim
