#include "core/errors.h"
#include "sim/scene_renderer.h"
#include "sim/shapes.h"
#include "sim/turntable_rig.h"
#include "test_support.h"

#include <opencv2/imgproc.hpp>
#include <tbb/global_control.h>

namespace scanstation::sim {
namespace {

constexpr double radius = 30.0;
const Eigen::Vector3d sphere_centre{12.0, 5.0, radius};  // object frame, standing on the platter

TriangleMesh sphere_object(int subdivisions) {
  TriangleMesh m = icosphere(subdivisions);
  m.vertices.positions *= radius;
  m.vertices.positions.rowwise() += sphere_centre.transpose();
  return m;
}

// Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d q = p - n.dot(p - a) * n;
  const auto inside = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return (v - u).cross(q - u).dot(n) >= 0; };
  if (inside(a, b) && inside(b, c) && inside(c, a)) return (p - q).norm();
  const auto segment = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const double t = std::clamp((p - u).dot(v - u) / (v - u).squaredNorm(), 0.0, 1.0);
    return (p - (u + t * (v - u))).norm();
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

struct Fixture {
  TurntableLaserRig rig = turntable_laser_rig(2 * radius, 60.0, 320, 240);
  SceneRenderer renderer{turntable_scene(sphere_object(3), rig, 60.0)};
};

TEST(SceneRenderer, GroundTruthPointsLieOnTheMeshAndProjectToTheirPixel) {
  Fixture f;
  const double angle = 0.7;
  const RenderedView view = f.renderer.cast(f.rig.camera, angle);
  const TriangleMesh& mesh = f.renderer.scene().object;
  const double diagonal = 2 * std::sqrt(3.0) * radius;
  int checked = 0;
  for (int r = 0; r < view.truth.kind.rows; r += 3)
    for (int c = 0; c < view.truth.kind.cols; c += 3) {
      const auto kind = static_cast<HitKind>(view.truth.kind.at<std::uint8_t>(r, c));
      if (kind == HitKind::none) continue;
      const cv::Vec3d q = view.truth.points.at<cv::Vec3d>(r, c);
      const Eigen::Vector3d p{q[0], q[1], q[2]};
      const Eigen::Vector3d station = turntable_rotation(angle) * p;
      const auto pixel = f.rig.camera.project(station);
      ASSERT_TRUE(pixel);
      EXPECT_NEAR(pixel->x(), c, 1e-6);
      EXPECT_NEAR(pixel->y(), r, 1e-6);
      EXPECT_NEAR(view.truth.depth.at<double>(r, c), (f.rig.camera.rotation * station + f.rig.camera.translation).z(), 1e-9);
      if (kind == HitKind::platter) {
        EXPECT_NEAR(p.z(), 0.0, 1e-9);
        continue;
      }
      double nearest = std::numeric_limits<double>::infinity();
      for (Eigen::Index t = 0; t < mesh.faces.rows(); ++t)
        nearest = std::min(nearest, point_triangle_distance(p, mesh.vertices.positions.row(mesh.faces(t, 0)),
                                                            mesh.vertices.positions.row(mesh.faces(t, 1)),
                                                            mesh.vertices.positions.row(mesh.faces(t, 2))));
      EXPECT_LE(nearest, 1e-6 * diagonal);
      ++checked;
    }
  EXPECT_GT(checked, 200);
}

// One renderer serves several cameras (a stereo rig has two) and keeps each
// camera's pixel rays: a view is the same bytes whichever cameras it cast
// for before, and a camera that differs in any lens or pose parameter gets
// its own rays.
TEST(SceneRenderer, EachCameraGetsItsOwnRaysWhateverWasCastBefore) {
  Fixture f;
  PinholeCamera turned = f.rig.camera, distorted = f.rig.camera, shifted = f.rig.camera;
  turned.rotation = Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY()).toRotationMatrix() * turned.rotation;
  distorted.distortion.k1 = -0.2;
  shifted.cx += 7.0;
  const auto same = [](const RenderedView& a, const RenderedView& b) {
    return cv::norm(a.truth.depth, b.truth.depth, cv::NORM_INF) == 0.0 && cv::norm(a.unlit, b.unlit, cv::NORM_INF) == 0.0;
  };
  std::vector<RenderedView> first;
  for (const PinholeCamera* camera : {&f.rig.camera, &turned, &distorted, &shifted}) first.push_back(f.renderer.cast(*camera, 0.4));
  for (std::size_t a = 0; a < first.size(); ++a)
    for (std::size_t b = a + 1; b < first.size(); ++b) EXPECT_FALSE(same(first[a], first[b])) << a << " " << b;
  std::size_t k = 0;
  for (const PinholeCamera* camera : {&shifted, &distorted, &turned, &f.rig.camera}) {
    Fixture fresh;
    const RenderedView again = f.renderer.cast(*camera, 0.4), alone = fresh.renderer.cast(*camera, 0.4);
    EXPECT_TRUE(same(again, alone)) << k;
    EXPECT_TRUE(same(again, first[3 - k])) << k;
    ++k;
  }
}

// Embree applies a device's thread count to the whole process (a TBB
// global_control): a renderer must leave the rest of the program's
// parallel work its cores.
TEST(SceneRenderer, LeavesTheProcessItsThreads) {
  const auto allowed = [] { return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism); };
  const std::size_t before = allowed();
  {
    Fixture f;
    f.renderer.cast(f.rig.camera, 0.1);
    EXPECT_EQ(allowed(), before);
  }
  EXPECT_EQ(allowed(), before);
}

TEST(SceneRenderer, SphereSilhouetteMatchesTheAnalyticProjection) {
  TurntableLaserRig rig = turntable_laser_rig(2 * radius, 60.0, 320, 240);
  SceneRenderer renderer{turntable_scene(sphere_object(6), rig, 60.0)};
  const double angle = 2.1;
  const RenderedView view = renderer.cast(rig.camera, angle);
  const Eigen::Vector3d centre = turntable_rotation(angle) * sphere_centre;
  const Eigen::Vector3d eye = rig.camera.centre();
  int inside = 0, mismatches = 0;
  for (int r = 0; r < view.truth.kind.rows; ++r)
    for (int c = 0; c < view.truth.kind.cols; ++c) {
      const Eigen::Vector3d d = rig.camera.ray_direction({c, r});
      const double miss = (centre - eye - (centre - eye).dot(d) * d).norm();  // ray–centre distance
      const bool analytic = miss < radius;
      const bool rendered = view.truth.kind.at<std::uint8_t>(r, c) == static_cast<std::uint8_t>(HitKind::object);
      inside += analytic;
      // The icosphere's facets lie within 1.2e-4 R of the sphere.
      if (analytic != rendered && std::abs(miss - radius) > 2e-4 * radius) ++mismatches;
    }
  EXPECT_GT(inside, 2000);
  EXPECT_EQ(mismatches, 0);
}

TEST(SceneRenderer, LaserOnAndOffDifferOnlyOnTheLitLaserLine) {
  Fixture f;
  const double angle = 0.3;
  const RenderedView view = f.renderer.cast(f.rig.camera, angle);
  SensorModel exact;
  exact.noise = false;
  const cv::Mat off = f.renderer.expose(view, {}, 1, exact);
  const cv::Mat on = f.renderer.expose(view, {0}, 1, exact);
  cv::Mat lit = view.laser[0] > 0;
  // The defocus blur spreads the line by a few pixels, no more.
  cv::dilate(lit, lit, cv::getStructuringElement(cv::MORPH_RECT, {7, 7}));
  cv::Mat changed = on != off;
  EXPECT_GT(cv::countNonZero(changed), 100);
  EXPECT_EQ(cv::countNonZero(changed & ~lit), 0);

  // Seen from above: lit spots lie in the beam and see the laser past the
  // sphere; the platter behind the sphere, in the plane, is in its shadow.
  const PinholeCamera top = PinholeCamera::look_at({0, -1, 300}, {0, 0, 0}, Eigen::Vector3d::UnitY(), 320, 320, 0.5);
  const RenderedView from_above = f.renderer.cast(top, angle);
  const LineLaser& laser = f.renderer.scene().lasers[0];
  const Eigen::Vector3d centre = turntable_rotation(angle) * sphere_centre;
  const auto sphere_blocks = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = (laser.plane.origin - p).normalized();
    const double t = (centre - p).dot(d);
    return t > 1e-6 && (centre - p - t * d).norm() < radius * (1 - 1e-3);
  };
  int shadowed = 0;
  for (int r = 0; r < top.height; ++r)
    for (int c = 0; c < top.width; ++c) {
      const cv::Vec3d q = from_above.truth.points.at<cv::Vec3d>(r, c);
      const Eigen::Vector3d p = turntable_rotation(angle) * Eigen::Vector3d(q[0], q[1], q[2]);
      const auto kind = static_cast<HitKind>(from_above.truth.kind.at<std::uint8_t>(r, c));
      if (from_above.laser[0].at<float>(r, c) > 0) {
        EXPECT_LE(std::abs(laser.plane.signed_distance(p)), 6 * laser.beam_sigma);
        EXPECT_FALSE(kind == HitKind::platter && sphere_blocks(p));
      } else if (kind == HitKind::platter && std::abs(laser.plane.signed_distance(p)) < 0.5 * laser.beam_sigma &&
                 sphere_blocks(p)) {
        ++shadowed;
      }
    }
  EXPECT_GT(shadowed, 3);
}

TEST(SceneRenderer, SameSeedSameBytesOtherSeedOtherNoise) {
  Fixture f;
  const RenderedView view = f.renderer.cast(f.rig.camera, 1.0);
  const cv::Mat a = f.renderer.expose(view, {1}, 42);
  const cv::Mat b = f.renderer.expose(f.renderer.cast(f.rig.camera, 1.0), {1}, 42);
  const cv::Mat c = f.renderer.expose(view, {1}, 43);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 0.0);
  // The noise has the modelled size: shot + read noise of about 1.5 grey levels here.
  cv::Mat difference;
  cv::subtract(a, c, difference, cv::noArray(), CV_32F);
  cv::Scalar mean, deviation;
  cv::meanStdDev(difference, mean, deviation);
  EXPECT_GT(deviation[0] / std::sqrt(2.0), 0.7);
  EXPECT_LT(deviation[0] / std::sqrt(2.0), 3.0);
}

TEST(SceneRenderer, RejectsMeshWithoutTriangles) {
  Scene scene;
  test::expect_error<InvalidInput>([&] { SceneRenderer renderer(scene); }, {"no triangles"});
}

}  // namespace
}  // namespace scanstation::sim

namespace scanstation::sim {
namespace {

TEST(SceneRenderer, ChessboardTargetTurnsWithThePlatterAndShowsItsSquares) {
  const TurntableLaserRig rig = turntable_laser_rig(60.0, 60.0, 320, 240);
  Scene scene;
  ChessboardTarget board;
  board.square = 8.0;
  board.origin = {-32.0, 0.0, 50.0};
  scene.board = board;
  const SceneRenderer renderer(scene);
  const double angle = 0.4;
  const RenderedView view = renderer.cast(rig.camera, angle);
  SensorModel exact;
  exact.noise = false;
  exact.defocus_sigma = 0;
  const cv::Mat frame = renderer.expose(view, {}, 1, exact);
  const Eigen::Vector3d normal = board.across.cross(board.down);
  int on_board = 0, dark = 0;
  for (int r = 0; r < view.truth.kind.rows; ++r)
    for (int c = 0; c < view.truth.kind.cols; ++c) {
      if (view.truth.kind.at<std::uint8_t>(r, c) != static_cast<std::uint8_t>(HitKind::board)) continue;
      ++on_board;
      const cv::Vec3d q = view.truth.points.at<cv::Vec3d>(r, c);
      const Eigen::Vector3d p{q[0], q[1], q[2]};
      EXPECT_NEAR(normal.dot(p - board.origin), 0.0, 1e-9);
      // The square a pixel shows follows from its ground-truth point.
      const double a = board.across.dot(p - board.origin) / board.square, b = board.down.dot(p - board.origin) / board.square;
      const bool square = a > -0.9 && a < board.columns - 0.1 && b > -0.9 && b < board.rows - 0.1 &&
                          std::abs(a - std::round(a)) > 0.1 && std::abs(b - std::round(b)) > 0.1;
      if (square && (static_cast<long>(std::floor(a)) + static_cast<long>(std::floor(b))) % 2 == 0) {
        ++dark;
        EXPECT_LT(frame.at<std::uint8_t>(r, c), 25);
      } else if (square) {
        EXPECT_GT(frame.at<std::uint8_t>(r, c), 30);
      }
    }
  EXPECT_GT(on_board, 5000);
  EXPECT_GT(dark, 1000);
}

}  // namespace
}  // namespace scanstation::sim
