// The simulated stereo rig and its random-dot projector.
#include "core/errors.h"
#include "sim/shapes.h"
#include "sim/stereo_rig.h"
#include "test_support.h"

namespace scanstation::sim {
namespace {

constexpr double radius = 25.0, platter_radius = 60.0;
const Eigen::Vector3d centre{10.0, -5.0, radius};

TriangleMesh sphere() {
  TriangleMesh m = icosphere(4);
  m.vertices.positions *= radius;
  m.vertices.positions.rowwise() += centre.transpose();
  return m;
}

TEST(StereoRig, BothCamerasFrameTheObjectSideBySide) {
  const StereoRig rig = stereo_rig(2 * radius, platter_radius, 320, 240);
  for (const PinholeCamera* camera : {&rig.left, &rig.right, &rig.projector.optics}) {
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 2 * radius),
                                     Eigen::Vector3d(platter_radius, 0, 0), Eigen::Vector3d(-platter_radius, 0, 0)}) {
      const auto pixel = camera->project(p);
      ASSERT_TRUE(pixel);
      EXPECT_GT(pixel->x(), 0);
      EXPECT_LT(pixel->x(), camera->width - 1);
      EXPECT_GT(pixel->y(), 0);
      EXPECT_LT(pixel->y(), camera->height - 1);
    }
  }
  const Eigen::Vector3d baseline = rig.right.centre() - rig.left.centre();
  EXPECT_GT(baseline.x(), 0);
  EXPECT_NEAR(baseline.y(), 0, 1e-9);
  EXPECT_NEAR(baseline.z(), 0, 1e-9);
  EXPECT_NEAR((rig.projector.optics.centre() - 0.5 * (rig.left.centre() + rig.right.centre())).norm(), 0, 1e-9);
  test::expect_error<InvalidInput>([] { stereo_rig(0, platter_radius, 320, 240); }, {"positive"});
}

TEST(DotProjector, SeededDotsShadowedByTheObjectAndSwitchable) {
  const StereoRig rig = stereo_rig(2 * radius, platter_radius, 320, 240);
  const SceneRenderer with(stereo_scene(sphere(), rig, platter_radius, true));
  const SceneRenderer without(stereo_scene(sphere(), rig, platter_radius, false));
  const double angle = 0.4;
  const RenderedView view = with.cast(rig.left, angle), plain = without.cast(rig.left, angle);
  ASSERT_FALSE(view.dots.empty());
  EXPECT_TRUE(plain.dots.empty());
  // Switched off, the projector leaves the frame as it is without one.
  EXPECT_EQ(cv::countNonZero(with.expose(view, {}, 7, {}, false) != without.expose(plain, {}, 7)), 0);
  EXPECT_GT(cv::countNonZero(with.expose(view, {}, 7) != without.expose(plain, {}, 7)), 1000);

  // About `fill` of the lit object is dotted; nothing in the object's shadow.
  const Eigen::Vector3d projector = turntable_rotation(angle).transpose() * rig.projector.optics.centre();
  int object = 0, dotted = 0, shadowed = 0;
  for (int r = 0; r < 240; ++r)
    for (int c = 0; c < 320; ++c) {
      const auto kind = static_cast<HitKind>(view.truth.kind.at<std::uint8_t>(r, c));
      const cv::Vec3d q = view.truth.points.at<cv::Vec3d>(r, c);
      const Eigen::Vector3d p{q[0], q[1], q[2]};
      const float dots = view.dots.at<float>(r, c);
      if (kind == HitKind::object) {
        const Eigen::Vector3d normal = (p - centre).normalized();
        if (normal.dot((projector - p).normalized()) < 0.3) continue;
        ++object;
        dotted += dots > 0;
      } else if (kind == HitKind::platter) {
        // Does the segment from p to the projector pass through the sphere?
        const Eigen::Vector3d d = (projector - p).normalized();
        const double t = std::clamp((centre - p).dot(d), 0.0, (projector - p).norm());
        if ((p + t * d - centre).norm() < radius - 0.5) {
          ++shadowed;
          EXPECT_EQ(dots, 0.0f);
        }
      }
    }
  EXPECT_GT(object, 2000);
  EXPECT_GT(shadowed, 200);
  EXPECT_NEAR(static_cast<double>(dotted) / object, rig.projector.fill, 0.1);

  // Another seed, other dots; the same seed, the same.
  StereoRig reseeded = rig;
  reseeded.projector.seed = 2;
  const SceneRenderer other(stereo_scene(sphere(), reseeded, platter_radius, true));
  EXPECT_GT(cv::countNonZero(other.cast(rig.left, angle).dots != view.dots), 1000);
  EXPECT_EQ(cv::countNonZero(with.cast(rig.left, angle).dots != view.dots), 0);
}

}  // namespace
}  // namespace scanstation::sim
