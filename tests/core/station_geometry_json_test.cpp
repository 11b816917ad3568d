#include "core/io/station_geometry_json.h"

#include "core/errors.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace scanstation {
namespace {
using test::expect_error;

PinholeCamera example_camera() {
  PinholeCamera camera = PinholeCamera::look_at({10, -300, 80}, {0, 0, 60}, {0, 0, 1}, 1280, 960, 0.6);
  camera.distortion = {-0.12, 0.05, -0.01, 0.001, -0.0007};
  return camera;
}

TEST(StationGeometryJson, CameraRoundTripsThroughText) {
  const PinholeCamera camera = example_camera();
  const auto text = to_json(camera).dump(2);
  const PinholeCamera back = pinhole_camera_from_json(nlohmann::json::parse(text), "test");
  EXPECT_EQ(back.width, 1280);
  EXPECT_EQ(back.height, 960);
  EXPECT_DOUBLE_EQ(back.fx, camera.fx);
  EXPECT_DOUBLE_EQ(back.distortion.k3, camera.distortion.k3);
  EXPECT_DOUBLE_EQ(back.distortion.p2, camera.distortion.p2);
  EXPECT_EQ((back.rotation - camera.rotation).norm(), 0.0);
  EXPECT_EQ((back.translation - camera.translation).norm(), 0.0);
  const Point3 p{3, 4, 50};
  EXPECT_EQ(*back.project(p), *camera.project(p));
}

TEST(StationGeometryJson, LaserPlaneRoundTripsAndNormalises) {
  auto value = to_json(LaserPlane{{1, 2, 3}, {0, 0.6, 0.8}});
  EXPECT_EQ(laser_plane_from_json(value, "t").origin, Point3(1, 2, 3));
  value["normal"] = {0, 3, 4};
  EXPECT_NEAR(laser_plane_from_json(value, "t").normal.y(), 0.6, 1e-15);
}

TEST(StationGeometryJson, BadFieldsAreNamed) {
  auto camera = to_json(example_camera());
  camera.erase("fy");
  expect_error<InvalidInput>([&] { pinhole_camera_from_json(camera, "calibration.json: camera"); },
                             {"calibration.json: camera", "fy"});
  camera = to_json(example_camera());
  camera["rotation"][1] = {0, 2, 0};
  expect_error<InvalidInput>([&] { pinhole_camera_from_json(camera, "m"); }, {"m.rotation", "orthonormal"});
  camera = to_json(example_camera());
  camera["distortion"]["k1"] = "x";
  expect_error<InvalidInput>([&] { pinhole_camera_from_json(camera, "m"); }, {"m.distortion.k1", "finite number"});
  camera = to_json(example_camera());
  camera["width"] = -3;
  expect_error<InvalidInput>([&] { pinhole_camera_from_json(camera, "m"); }, {"m.width", "positive integer"});
  auto laser = to_json(LaserPlane{});
  laser["normal"] = {0, 0, 0};
  expect_error<InvalidInput>([&] { laser_plane_from_json(laser, "m.lasers[0]"); }, {"m.lasers[0].normal", "non-zero"});
  laser["origin"] = {1, 2};
  expect_error<InvalidInput>([&] { laser_plane_from_json(laser, "m"); }, {"m.origin", "3 numbers"});
}

}  // namespace
}  // namespace scanstation
