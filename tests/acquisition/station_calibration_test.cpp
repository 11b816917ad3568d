// Laser plane and turntable axis calibration on the simulator, end to end:
// the camera calibrated from rendered chessboards, then the board on the
// platter at several turntable angles (axis) and crossed by the lasers
// (planes); the recovered parameters are compared with the rig's truth.
// Also: outlier peaks, degenerate inputs, the calibration file.
#include "acquisition/camera_calibration.h"
#include "acquisition/laser_plane_calibration.h"
#include "acquisition/station_calibration.h"
#include "acquisition/turntable_axis_calibration.h"
#include "core/errors.h"
#include "sim/calibration_views.h"
#include "sim/simulated_turntable.h"
#include "sim/stereo_rig.h"
#include "sim/turntable_rig.h"
#include "test_support.h"

#include <cmath>
#include <fstream>
#include <numbers>
#include <random>

namespace scanstation::acquisition {
namespace {

constexpr double degree = std::numbers::pi / 180.0;
constexpr double platter_radius = 60.0;
const cv::Size board_size{9, 6};
constexpr double square = 8.0;

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

// The rig and its scene; the camera calibrated from rendered boards on first use.
struct Station {
  sim::TurntableLaserRig rig = sim::turntable_laser_rig(80.0, platter_radius, 640, 480);
  sim::Scene scene;

  Station() {
    scene.platter_radius = platter_radius;
    scene.lasers = rig.lasers;
  }
  sim::BoardFrames render(const sim::BoardPlacement& placement, bool lasers, std::uint64_t seed) const {
    return sim::render_board(scene, placement, rig.camera, lasers, seed);
  }
  // Calibrated intrinsics, identity pose: what the turntable and laser calibrations see through.
  const PinholeCamera& camera() const {
    static const PinholeCamera calibrated = [this] {
      std::vector<std::vector<cv::Point2f>> corners;
      std::uint64_t seed = 100;
      for (const sim::BoardPlacement& placement : sim::camera_placements(board_size.width, board_size.height, square))
        if (const auto found = find_chessboard(render(placement, false, ++seed).laser_off, board_size))
          corners.push_back(*found);
      return pinhole_camera(calibrate_camera(corners, board_size, square, {640, 480}), {640, 480});
    }();
    return calibrated;
  }
};

const Station& station() {
  static const Station s;
  return s;
}

struct TurntableViews {
  std::vector<BoardPose> poses;
  std::vector<double> angles;
  double lowest = 0;
};

TurntableViews turntable_views(const std::vector<sim::BoardPlacement>& placements) {
  const Station& s = station();
  TurntableViews views;
  std::uint64_t seed = 200;
  for (const sim::BoardPlacement& placement : placements) {
    const auto corners = find_chessboard(s.render(placement, false, ++seed).laser_off, board_size);
    if (!corners) continue;
    views.poses.push_back(board_pose(*corners, board_size, square, s.camera()));
    views.angles.push_back(placement.angle);
  }
  views.lowest = sim::lowest_corner_height(placements.front().board);
  return views;
}

TEST(TurntableAxisCalibration, SimulatedBoardRecoversTheAxisAndTheCameraPose) {
  const Station& s = station();
  const std::vector<sim::BoardPlacement> placements = sim::turntable_placements(board_size.width, board_size.height, square);
  const TurntableViews views = turntable_views(placements);
  ASSERT_GE(views.poses.size(), 7u);
  const TurntableAxis axis = calibrate_turntable_axis(views.poses, views.angles, board_size, square, views.lowest);
  const PinholeCamera& truth = s.rig.camera;
  const Eigen::Vector3d true_axis = truth.rotation.col(2);  // station z in the camera frame
  const double axis_error = angle_between(axis.direction, true_axis);
  const double origin_error = (axis.origin - truth.translation).norm();
  const PinholeCamera placed = place_camera(s.camera(), axis);
  const double rotation_error = Eigen::AngleAxisd(placed.rotation * truth.rotation.transpose()).angle();
  std::printf("turntable axis: %zu views, axis error %.4f deg, origin error %.3f mm, camera pose error %.4f deg / "
              "%.3f mm; residuals RMS %.4f mm, max %.4f mm, angles RMS %.4f deg\n",
              views.poses.size(), axis_error / degree, origin_error, rotation_error / degree,
              (placed.centre() - truth.centre()).norm(), axis.rms, axis.max, axis.angle_rms / degree);
  EXPECT_LT(axis_error, 0.1 * degree);  // the 0.1°
  EXPECT_LT(origin_error, 1.0);
  EXPECT_LT(rotation_error, 0.2 * degree);
  EXPECT_LT(axis.rms, 0.1);
  EXPECT_LT(axis.angle_rms, 0.1 * degree);
  EXPECT_EQ(axis.measured_angles.size(), views.poses.size());

  // Degenerate and short inputs.
  const std::vector<BoardPose> two(views.poses.begin(), views.poses.begin() + 2);
  test::expect_error<InvalidInput>(
      [&] { calibrate_turntable_axis(two, {views.angles[0], views.angles[1]}, board_size, square, 0); }, {"at least 3"});
  const std::vector<BoardPose> same(4, views.poses.front());
  test::expect_error<InvalidInput>(
      [&] { calibrate_turntable_axis(same, {0.0, 0.1, 0.2, 0.3}, board_size, square, 0); }, {"turned by at most"});
  test::expect_error<InvalidInput>(
      [&] { calibrate_turntable_axis(views.poses, std::vector<double>(views.poses.size(), 0.5), board_size, square, 0); },
      {"span only"});
}

struct LaserViews {
  std::vector<std::vector<LaserBoardView>> by_laser;
};

LaserViews laser_views(const std::vector<sim::BoardPlacement>& placements) {
  const Station& s = station();
  LaserViews views;
  views.by_laser.resize(s.rig.lasers.size());
  std::uint64_t seed = 300;
  for (const sim::BoardPlacement& placement : placements) {
    const sim::BoardFrames frames = s.render(placement, true, seed += 10);
    const auto corners = find_chessboard(frames.laser_off, board_size);
    for (std::size_t l = 0; l < frames.laser_on.size(); ++l)
      views.by_laser[l].push_back({frames.laser_off, frames.laser_on[l], corners.value_or(std::vector<cv::Point2f>{})});
  }
  return views;
}

LaserPlaneOptions laser_options() {
  LaserPlaneOptions options;
  options.inner_corners = board_size;
  options.square_size = square;
  return options;
}

TEST(LaserPlaneCalibration, SimulatedBoardRecoversBothPlanesAndIgnoresOutlierPeaks) {
  const Station& s = station();
  const LaserViews views = laser_views(sim::laser_placements(board_size.width, board_size.height, square));
  for (std::size_t l = 0; l < views.by_laser.size(); ++l) {
    const LaserPlaneCalibration found = calibrate_laser_plane(views.by_laser[l], s.camera(), laser_options());
    const LaserPlane truth = to_camera_frame(s.rig.lasers[l].plane, s.rig.camera);
    const double normal_error = std::min(angle_between(found.plane.normal, truth.normal),
                                         angle_between(-found.plane.normal, truth.normal));
    const double offset_error = std::abs(truth.signed_distance(found.plane.origin));
    std::printf("laser %zu: normal error %.4f deg, offset %.4f mm; %zu of %zu points, RMS %.4f mm, max %.4f mm, "
                "spread %.1f mm\n",
                l, normal_error / degree, offset_error, found.inliers, found.points, found.rms, found.max, found.spread);
    EXPECT_LT(normal_error, 0.1 * degree);  // the 0.1°
    EXPECT_LT(offset_error, 0.3);
    EXPECT_GT(found.inliers, 0.9 * static_cast<double>(found.points));
    EXPECT_LT(found.rms, 0.1);
    EXPECT_EQ(found.points_per_view.size(), views.by_laser[l].size());
  }

  // Outlier peaks (reflections, a second light source): a quarter of the
  // stripe centres moved to random columns inside the board.
  const LaserPlaneOptions options = laser_options();
  std::vector<Eigen::Vector3d> clean, noisy;
  std::mt19937_64 engine(7);
  for (const LaserBoardView& view : views.by_laser[0]) {
    if (view.corners.empty()) continue;
    const BoardPose pose = board_pose(view.corners, board_size, square, s.camera());
    LaserLine line = extract_laser_line(view.laser_on, view.laser_off, options.line);
    const std::vector<Eigen::Vector3d> good = laser_points_on_board(line, pose, s.camera(), options);
    clean.insert(clean.end(), good.begin(), good.end());
    for (std::size_t i = 0; i < line.peaks.size(); i += 4) line.peaks[i].x += static_cast<double>(engine() % 160) - 80.0;
    const std::vector<Eigen::Vector3d> bad = laser_points_on_board(line, pose, s.camera(), options);
    noisy.insert(noisy.end(), bad.begin(), bad.end());
  }
  const LaserPlaneCalibration reference = fit_plane_robust(clean, options);
  const LaserPlaneCalibration robust = fit_plane_robust(noisy, options);
  const double drift = std::min(angle_between(reference.plane.normal, robust.plane.normal),
                                angle_between(-reference.plane.normal, robust.plane.normal));
  std::printf("outlier peaks: %zu of %zu points kept, normal moved %.4f deg\n", robust.inliers, robust.points, drift / degree);
  EXPECT_LT(drift, 0.02 * degree);
  EXPECT_LT(static_cast<double>(robust.inliers), 0.85 * static_cast<double>(robust.points));

  // The same board pose every time: the stripes coincide, no plane.
  std::vector<LaserBoardView> repeated(3, views.by_laser[0].front());
  test::expect_error<InvalidInput>([&] { calibrate_laser_plane(repeated, s.camera(), laser_options()); }, {"one line"});
  test::expect_error<InvalidInput>(
      [&] { calibrate_laser_plane({views.by_laser[0].front()}, s.camera(), laser_options()); }, {"at least 2"});
}

TEST(CameraCalibration, ParallelBoardsAreAClearError) {
  // A small camera, one ray per pixel: noisy corners, where the normals
  // fitted with a wrong focal length look less parallel than they are (one
  // draw of the sensor noise once gave a focal length 120× the true one with
  // the fitted boards 135° apart). Several draws: the refusal must not
  // depend on the noise.
  const PinholeCamera camera = sim::turntable_laser_rig(80.0, platter_radius, 320, 240).camera;
  for (const std::uint64_t first_seed : {400, 500, 600, 700}) {
    std::vector<std::vector<cv::Point2f>> corners;
    std::uint64_t seed = first_seed;
    for (const double shift : {-20.0, 0.0, 20.0})
      for (const double height : {30.0, 45.0}) {
        const sim::BoardPlacement placement{sim::standing_board(9, 6, square, 0.3, {shift, 0.0, height}), 0.0};
        if (const auto found = find_chessboard(
                sim::render_board(station().scene, placement, camera, false, ++seed, 1).laser_off, board_size))
          corners.push_back(*found);
      }
    ASSERT_GE(corners.size(), 4u);
    test::expect_error<InvalidInput>([&] { calibrate_camera(corners, board_size, square, {320, 240}); },
                                     {"nearly parallel"});
  }
}

// A calibration with every part, as the commands build it.
StationCalibration full_calibration(const drivers::StationDescription& description) {
  const Station& s = station();
  StationCalibration c;
  c.software_version = "test";
  c.created = c.updated = "2026-12-01T17:00:00Z";
  c.station = station_fingerprint(description);
  CameraPart camera;
  camera.date = c.created;
  camera.views = 12;
  camera.camera = s.rig.camera;  // set_camera drops the pose: the turntable part places it
  camera.rms = 0.07;
  camera.per_view_rms = {0.06, 0.08};
  EXPECT_TRUE(set_camera(c, camera).empty());
  TurntablePart turntable;
  turntable.date = c.created;
  turntable.axis_camera = s.rig.camera.rotation.col(2);
  turntable.origin_camera = s.rig.camera.translation;
  turntable.angles = {0.0, 0.5};
  turntable.measured_angles = {0.0, 0.5001};
  set_turntable(c, turntable);
  for (int l = 0; l < 2; ++l) {
    LaserPart laser;
    laser.index = 1 - l;
    laser.date = c.created;
    laser.views = 6;
    laser.plane = s.rig.lasers[static_cast<std::size_t>(1 - l)].plane;
    laser.rms = 0.01;
    laser.inliers = laser.points = 900;
    set_laser(c, laser);
  }
  StereoPart stereo;
  stereo.date = c.created;
  stereo.pairs = 13;
  stereo.left = stereo.right = camera.camera;
  stereo.right.translation = {-3.3, 0.0, 0.0};
  stereo.per_view_rms = {{0.4, 0.5}};
  c.stereo = stereo;
  return c;
}

TEST(StationCalibrationFile, RoundTripPlacesTheCameraAndKeepsEveryPart) {
  const drivers::StationDescription description;
  const StationCalibration c = full_calibration(description);
  // The turntable part placed the camera where the rig has it.
  ASSERT_TRUE(c.camera && c.camera->posed);
  EXPECT_LT((c.camera->camera.rotation - station().rig.camera.rotation).norm(), 1e-9);
  EXPECT_LT((c.camera->camera.translation - station().rig.camera.translation).norm(), 1e-9);
  ASSERT_EQ(c.lasers.size(), 2u);
  EXPECT_EQ(c.lasers[0].index, 0);

  test::ScratchFolder folder;
  const auto file = folder / "calibration.json";
  write_station_calibration(file, c, io::Overwrite::refuse);
  test::expect_error<InvalidInput>([&] { write_station_calibration(file, c, io::Overwrite::refuse); }, {"calibration.json"});
  const StationCalibration back = read_station_calibration(file);
  EXPECT_EQ(to_json(back), to_json(c));
  EXPECT_EQ(back.source, file);
  EXPECT_NO_THROW(check_calibration_matches(back, description));
  EXPECT_NO_THROW(check_calibration_complete(back, CalibrationNeed::lasers, 2));
  EXPECT_NO_THROW(check_calibration_complete(back, CalibrationNeed::stereo));
  // The stereo part lists its rectification: Q maps disparity to depth with
  // the pair's baseline (Q(3,2) = −1/Tx; here 3.3 apart along x).
  const nlohmann::json rectification = to_json(back)["stereo"]["rectification"];
  ASSERT_EQ(rectification["Q"].size(), 4u);
  EXPECT_NEAR(std::abs(1.0 / rectification["Q"][3][2].get<double>()), 3.3, 1e-9);
  EXPECT_EQ(rectification["P2"][0].size(), 4u);
  test::expect_error<InvalidInput>([&] { check_calibration_complete(back, CalibrationNeed::lasers, 3); },
                                   {"calibration.json", "laser 2", "calibrate laser"});

  // A new camera calibration drops what was measured through the old one.
  StationCalibration recalibrated = back;
  EXPECT_THAT(set_camera(recalibrated, *back.camera), testing::ElementsAre("turntable", "laser 0", "laser 1"));
  test::expect_error<InvalidInput>([&] { check_calibration_complete(recalibrated, CalibrationNeed::camera_pose); },
                                   {"calibrate turntable"});
  // Re-calibrating the turntable keeps the lasers where they are relative to the camera.
  StationCalibration moved = back;
  TurntablePart other = *back.turntable;
  other.origin_camera += Eigen::Vector3d(5.0, 0.0, 0.0);
  set_turntable(moved, other);
  const LaserPlane before = to_camera_frame(back.lasers[0].plane, back.camera->camera);
  const LaserPlane after = to_camera_frame(moved.lasers[0].plane, moved.camera->camera);
  EXPECT_LT((before.normal - after.normal).norm(), 1e-9);
  EXPECT_LT(std::abs(before.signed_distance(after.origin)), 1e-9);
}

TEST(StationCalibrationFile, MismatchedStationAndDamagedFilesAreRefusedWithTheField) {
  const drivers::StationDescription description;
  StationCalibration c = full_calibration(description);
  c.source = "cal.json";
  drivers::StationDescription other = description;
  other.camera.format.size = {1280, 960};
  other.lasers.push_back(drivers::LaserRole{});
  test::expect_error<InvalidInput>([&] { check_calibration_matches(c, other); },
                                   {"cal.json", "camera.width: calibrated 640, station 1280", "lasers: calibrated 1, station 2",
                                    "recalibrate"});
  drivers::StationDescription real = description;
  real.camera.backend = "v4l2";
  test::expect_error<InvalidInput>([&] { check_calibration_matches(c, real); },
                                   {"camera.backend: calibrated \"sim\", station \"v4l2\""});

  test::ScratchFolder folder;
  const auto write = [&](const std::string& text) {
    std::ofstream(folder / "bad.json") << text;
    return folder / "bad.json";
  };
  nlohmann::json document = to_json(c);
  document["lasers"][1]["plane"]["normal"] = {0, 0, 0};
  test::expect_error<InvalidInput>([&] { read_station_calibration(write(document.dump(2))); },
                                   {"bad.json", "lasers[1].plane.normal"});
  document = to_json(c);
  document["camera"]["geometry"].erase("fx");
  test::expect_error<InvalidInput>([&] { read_station_calibration(write(document.dump(2))); },
                                   {"bad.json", "camera.geometry", "\"fx\""});
  document = to_json(c);
  document["station"]["devices"]["camera"]["width"] = 800;
  test::expect_error<InvalidInput>([&] { read_station_calibration(write(document.dump(2))); },
                                   {"station.fingerprint", "edited"});
  test::expect_error<FormatError>([&] { read_station_calibration(write("{\n  \"format\": \n")); }, {"bad.json:", "JSON"});
  test::expect_error<InvalidInput>([&] { read_station_calibration(write("{\"format\": \"other\"}")); },
                                   {"not a scanstation calibration"});
}

TEST(StationCalibrationFile, StereoPairPlacedOnTheTurntableWhereTheRigHasIt) {
  // The simulated stereo rig's truth, as a stereo calibration and the axis
  // seen by its left camera would give it.
  const sim::StereoRig rig = sim::stereo_rig(sim::kSimulatedRigHeight, sim::kSimulatedPlatterRadius, 640, 480);
  StereoPart stereo;
  stereo.date = "2026-12-01T17:00:00Z";
  stereo.pairs = 12;
  stereo.left = stereo.right = rig.left;
  stereo.right.distortion = rig.right.distortion;
  stereo.right.rotation = rig.right.rotation * rig.left.rotation.transpose();
  stereo.right.translation = rig.right.translation - stereo.right.rotation * rig.left.translation;
  stereo.per_view_rms = {{0.1, 0.1}};
  TurntablePart turntable;
  turntable.date = stereo.date;
  turntable.axis_camera = rig.left.rotation.col(2);
  turntable.origin_camera = rig.left.translation;

  const drivers::StationDescription description = drivers::simulated_stereo_station();
  StationCalibration c;
  c.software_version = "test";
  c.created = c.updated = stereo.date;
  c.station = station_fingerprint(description);
  c.source = "stereo.json";
  set_stereo(c, stereo, std::nullopt);
  EXPECT_NO_THROW(check_calibration_complete(c, CalibrationNeed::stereo));
  test::expect_error<InvalidInput>([&] { check_calibration_complete(c, CalibrationNeed::stereo_pose); },
                                   {"stereo.json", "does not place the stereo pair on the turntable"});
  set_stereo(c, stereo, turntable);
  EXPECT_NO_THROW(check_calibration_complete(c, CalibrationNeed::stereo_pose));
  // y from the middle between the cameras to the axis: the rig's own frame.
  const auto [left, right] = stereo_cameras(*c.stereo);
  EXPECT_LT((left.rotation - rig.left.rotation).norm(), 1e-9);
  EXPECT_LT((left.translation - rig.left.translation).norm(), 1e-9);
  EXPECT_LT((right.rotation - rig.right.rotation).norm(), 1e-9);
  EXPECT_LT((right.translation - rig.right.translation).norm(), 1e-9);

  test::ScratchFolder folder;
  write_station_calibration(folder / "stereo.json", c, io::Overwrite::refuse);
  const StationCalibration back = read_station_calibration(folder / "stereo.json");
  EXPECT_EQ(to_json(back), to_json(c));
  EXPECT_EQ(to_json(back)["stereo"]["pose"], "station");

  // The fingerprint covers the right camera; a laser station's has none.
  EXPECT_TRUE(c.station.devices.contains("right_camera"));
  EXPECT_FALSE(station_fingerprint(drivers::StationDescription{}).devices.contains("right_camera"));
  drivers::StationDescription other = description;
  other.right_camera->format.format = drivers::PixelFormat::yuyv;
  test::expect_error<InvalidInput>([&] { check_calibration_matches(back, other); },
                                   {"stereo.json", "right_camera.format: calibrated"});
}

}  // namespace
}  // namespace scanstation::acquisition
