// Camera calibration on the simulator: chessboard views rendered on the
// platter at several poses recover the true intrinsics and distortion.
#include "acquisition/camera_calibration.h"
#include "core/errors.h"
#include "sim/scene_renderer.h"
#include "sim/turntable_rig.h"
#include "test_support.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

namespace scanstation::acquisition {
namespace {

// A 9×6 board of 8 mm squares standing on the platter, tilted back by `tilt`
// (radians from vertical), its middle at height `height`.
sim::ChessboardTarget board(double tilt, double height, double shift) {
  sim::ChessboardTarget b;
  b.columns = 9;
  b.rows = 6;
  b.square = 8.0;
  b.across = Eigen::Vector3d::UnitX();
  b.down = Eigen::Vector3d(0, -std::sin(tilt), -std::cos(tilt));
  b.origin = Eigen::Vector3d(shift, 0, height) - 4.0 * b.square * b.across - 2.5 * b.square * b.down;
  return b;
}

// The camera at k times the resolution: pixel (u, v) of the camera covers
// k × k pixels of this one, so averaging them integrates the pixel's area
// (one ray per pixel centre would alias the board's edges).
PinholeCamera supersampled(const PinholeCamera& camera, int k) {
  PinholeCamera fine = camera;
  fine.width *= k;
  fine.height *= k;
  fine.fx *= k;
  fine.fy *= k;
  fine.cx = k * camera.cx + 0.5 * (k - 1);
  fine.cy = k * camera.cy + 0.5 * (k - 1);
  return fine;
}

TEST(CameraCalibration, SimulatedChessboardsRecoverTheTrueCamera) {
  const sim::TurntableLaserRig rig = sim::turntable_laser_rig(80.0, 60.0, 640, 480);
  constexpr int k = 2;
  const PinholeCamera fine = supersampled(rig.camera, k);
  sim::SensorModel sensor;
  sensor.defocus_sigma *= k;
  std::vector<std::vector<cv::Point2f>> corners;
  int views = 0;
  // Varied tilt, turn, height and sideways shift, so that the corners reach
  // the edges of the image, where the distortion shows.
  for (const double tilt : {0.15, 0.55, 0.9})
    for (const double angle : {-0.6, -0.2, 0.2, 0.6}) {
      sim::Scene scene;
      scene.platter_radius = 60.0;
      const double side = views % 2 == 0 ? 1.0 : -1.0;
      scene.board = board(tilt, 40.0 + 18.0 * side * std::cos(3 * angle), 25.0 * side);
      const sim::SceneRenderer renderer(scene);
      cv::Mat frame;
      cv::resize(renderer.expose(renderer.cast(fine, angle), {}, static_cast<std::uint64_t>(++views), sensor), frame,
                 {rig.camera.width, rig.camera.height}, 0, 0, cv::INTER_AREA);
      if (const auto found = find_chessboard(frame, {9, 6})) corners.push_back(*found);
    }
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
