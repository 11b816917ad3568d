// Camera calibration on the simulator: chessboard views rendered on the
// platter at several poses recover the true intrinsics and distortion.
#include "acquisition/camera_calibration.h"
#include "core/errors.h"
#include "sim/calibration_views.h"
#include "sim/turntable_rig.h"
#include "test_support.h"

#include <cmath>

namespace scanstation::acquisition {
namespace {

TEST(CameraCalibration, SimulatedChessboardsRecoverTheTrueCamera) {
  const sim::TurntableLaserRig rig = sim::turntable_laser_rig(80.0, 60.0, 640, 480);
  std::vector<std::vector<cv::Point2f>> corners;
  const std::vector<sim::BoardPlacement> placements = sim::camera_placements(9, 6, 8.0);
  // Varied tilt, turn, height and sideways shift, so that the corners reach
  // the edges of the image, where the distortion shows.
  std::uint64_t seed = 0;
  for (const sim::BoardPlacement& placement : placements) {
    sim::Scene scene;
    scene.platter_radius = 60.0;
    const cv::Mat frame = sim::render_board(scene, placement, rig.camera, false, ++seed).laser_off;
    if (const auto found = find_chessboard(frame, {9, 6})) corners.push_back(*found);
  }
  const std::size_t views = placements.size();
  ASSERT_GE(corners.size(), 6u) << "the board was found in " << corners.size() << " of " << views << " views";
  const CameraIntrinsics camera = calibrate_camera(corners, {9, 6}, 8.0, {640, 480});
  const PinholeCamera& truth = rig.camera;
  std::printf("simulated calibration: %zu views, RMS %.3f px, fx %.2f (true %.2f), fy %.2f, cx %.2f (%.2f), cy %.2f (%.2f), "
              "k1 %.4f (%.4f)\n",
              corners.size(), camera.rms, camera.camera_matrix(0, 0), truth.fx, camera.camera_matrix(1, 1),
              camera.camera_matrix(0, 2), truth.cx, camera.camera_matrix(1, 2), truth.cy, camera.distortion.at<double>(0),
              truth.distortion.k1);
  EXPECT_LT(camera.rms, 0.15);
  EXPECT_EQ(camera.per_view_rms.size(), corners.size());
  EXPECT_NEAR(camera.camera_matrix(0, 0) / truth.fx, 1.0, 0.005);  // the 0.5%
  EXPECT_NEAR(camera.camera_matrix(1, 1) / truth.fy, 1.0, 0.005);
  EXPECT_NEAR(camera.camera_matrix(0, 2), truth.cx, 5.0);
  EXPECT_NEAR(camera.camera_matrix(1, 2), truth.cy, 5.0);
  EXPECT_NEAR(camera.distortion.at<double>(0), truth.distortion.k1, 0.03);
  test::expect_error<InvalidInput>([&] { calibrate_camera({corners.front()}, {9, 6}, 6.0, {640, 480}); },
                                   {"at least 3"});
}

}  // namespace
}  // namespace scanstation::acquisition
