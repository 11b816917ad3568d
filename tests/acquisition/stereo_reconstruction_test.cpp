// Stereo reconstruction: the reprojection chain on a synthetic disparity map,
// then end to end on the simulated stereo rig — views of texture-less
// objects at several turntable angles with the random-dot projector, fused
// in the object frame and compared with the true surface.
#include "acquisition/scan_accuracy.h"
#include "acquisition/stereo_reconstruction.h"
#include "acquisition/view_fusion.h"
#include "core/errors.h"
#include "sim/sampling.h"
#include "sim/shapes.h"
#include "sim/random.h"
#include "sim/stereo_rig.h"
#include "test_support.h"

#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>

#include <numbers>
#include <tuple>

namespace scanstation::acquisition {
namespace {

constexpr double platter_radius = 60.0;

Eigen::Matrix3d eigen33(const cv::Mat& m) {
  Eigen::Matrix3d out;
  cv::cv2eigen(m, out);
  return out;
}

// Depth Z(x, y) = 180 + 0.2 (x − 80) − 0.1 (y − 60) in the rectified left
// camera: every pixel's disparity is where the right rectified camera (P2)
// sees that point. disparity_to_points must give back the very points, also
// after fit_disparity_range moved the right view.
TEST(StereoReconstruction, DisparityReprojectsToThePointsInTheObjectFrame) {
  const sim::StereoRig rig = sim::stereo_rig(60.0, platter_radius, 160, 120);
  StereoStation station = stereo_station(rig.left, rig.right);
  fit_disparity_range(station, platter_radius, 60.0);
  const cv::Matx34d P1 = station.calibration.p1, P2 = station.calibration.p2;
  const double f = P1(0, 0), cx = P1(0, 2), cy = P1(1, 2);
  const double angle = 0.9;
  cv::Mat disparity(120, 160, CV_32F);
  std::vector<Eigen::Vector3d> truth;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      const double Z = 180 + 0.2 * (x - 80) - 0.1 * (y - 60);
      const Eigen::Vector3d X{(x - cx) * Z / f, (y - cy) * Z / f, Z};
      const cv::Vec3d right = P2 * cv::Vec4d(X.x(), X.y(), X.z(), 1.0);
      disparity.at<float>(y, x) = static_cast<float>(x - right[0] / right[2]);
      const Eigen::Vector3d left_camera = eigen33(station.calibration.r1).transpose() * X;
      const Eigen::Vector3d station_point = rig.left.rotation.transpose() * (left_camera - rig.left.translation);
      truth.push_back(turntable_rotation(angle).transpose() * station_point);
    }
  StereoReconstructionOptions options;
  options.minimum_height = -std::numeric_limits<double>::infinity();
  options.discontinuity = 0;
  options.minimum_texture = 0;  // a flat grey frame
  LaserScanPoints points;
  const cv::Mat grey(120, 160, CV_8U, cv::Scalar(90));
  disparity_to_points(station, disparity, grey, angle, points, options);
  ASSERT_EQ(points.cloud.size(), 160 * 120);
  double worst = 0;
  for (Eigen::Index i = 0; i < points.cloud.size(); ++i)
    // float disparities: 1e-7 relative, times Z / d
    worst = std::max(worst, (points.cloud.positions.row(i).transpose() - truth[static_cast<std::size_t>(i)]).norm());
  EXPECT_LT(worst, 1e-3);
  EXPECT_EQ(points.cloud.colors(0, 1), 90);
  ASSERT_EQ(points.confidence.size(), truth.size());
  EXPECT_GT(points.confidence.front(), 0.0);
  test::expect_error<InvalidInput>([&] { disparity_to_points(station, disparity, grey(cv::Rect(0, 0, 10, 10)), angle, points); },
                                   {"size"});
}

// A plane's disparity is affine in the rectified frame (1/Z is affine in the
// pixel for a plane): d = 40 + 0.05 (x − 80) − 0.03 (y − 60), and with
// `step` more from column 83 on (a second plane behind a depth edge that
// runs through the cells of column 80, three pixels off their centres).
cv::Mat planar_disparity(double step) {
  cv::Mat disparity(120, 160, CV_32F);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x)
      disparity.at<float>(y, x) = static_cast<float>(40 + 0.05 * (x - 80) - 0.03 * (y - 60) + (x >= 83 ? step : 0.0));
  return disparity;
}

// The plane through the reprojected points (least squares): unit normal and
// offset.
std::pair<Eigen::Vector3d, double> fitted_plane(const Eigen::MatrixX3d& P) {
  const Eigen::RowVector3d centre = P.colwise().mean();
  const Eigen::MatrixX3d centred = P.rowwise() - centre;
  const Eigen::JacobiSVD<Eigen::MatrixX3d> svd(centred, Eigen::ComputeThinV);
  const Eigen::Vector3d n = svd.matrixV().col(2);
  return {n, n.dot(centre.transpose())};
}

double rms_off(const Eigen::MatrixX3d& P, const std::pair<Eigen::Vector3d, double>& plane) {
  return std::sqrt(((P * plane.first).array() - plane.second).square().mean());
}

TEST(StereoReconstruction, CellMeansStayOnAPlaneAndAverageTheMatchingNoiseDown) {
  const sim::StereoRig rig = sim::stereo_rig(60.0, platter_radius, 160, 120);
  StereoStation station = stereo_station(rig.left, rig.right);
  StereoReconstructionOptions options;
  options.minimum_height = -std::numeric_limits<double>::infinity();
  options.minimum_texture = 0;
  options.discontinuity = 0;
  options.pixel_step = 8;
  const cv::Mat grey(120, 160, CV_8U, cv::Scalar(90));
  const auto points = [&](const cv::Mat& disparity, bool mean) {
    StereoReconstructionOptions o = options;
    o.cell_mean = mean;
    LaserScanPoints out;
    disparity_to_points(station, disparity, grey, 0.4, out, o);
    return out.cloud.positions;
  };
  cv::Mat clean = planar_disparity(0);
  const auto plane = fitted_plane(points(clean, false));
  ASSERT_LT(rms_off(points(clean, false), plane), 1e-4);
  // Unmatched pixels in the cells (every seventh): the mean of those left
  // is still on the plane.
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x)
      if ((x + 3 * y) % 7 == 0 && (x % 8 || y % 8)) clean.at<float>(y, x) = -1;
  const Eigen::MatrixX3d on = points(clean, true);
  EXPECT_EQ(on.rows(), 20 * 15);
  EXPECT_LT(((on * plane.first).array() - plane.second).abs().maxCoeff(), 1e-3);
  // Matching noise, independent per pixel (0.3 px): the cell means lie
  // several times closer to the plane than the pixels alone.
  sim::Random random(5);
  cv::Mat noisy = planar_disparity(0);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) noisy.at<float>(y, x) += static_cast<float>(0.3 * random.normal());
  const double alone = rms_off(points(noisy, false), plane), mean = rms_off(points(noisy, true), plane);
  EXPECT_LT(mean, alone / 4) << mean << " against " << alone;
  // A depth edge of 5 px: with the discontinuity tolerance each cell mean
  // keeps to one plane.
  const cv::Mat behind = planar_disparity(0) + 5.0;
  const auto far = fitted_plane(points(behind, false));
  options.discontinuity = 1.5;
  const Eigen::MatrixX3d split = points(planar_disparity(5), true);
  int on_near = 0, on_far = 0;
  for (Eigen::Index i = 0; i < split.rows(); ++i) {
    const double to_near = std::abs(split.row(i).dot(plane.first) - plane.second),
                 to_far = std::abs(split.row(i).dot(far.first) - far.second);
    EXPECT_LT(std::min(to_near, to_far), 1e-3) << i;
    (to_near < to_far ? on_near : on_far) += 1;
  }
  EXPECT_GT(on_near, 100);
  EXPECT_GT(on_far, 100);
}

// The disparities of every true object point lie in the searched range, and
// the rectified rows agree (the epipolar lines are rows).
TEST(StereoReconstruction, RectificationAndDisparityRangeCoverTheWorkingVolume) {
  const sim::StereoRig rig = sim::stereo_rig(60.0, platter_radius, 320, 240);
  const StereoStation unfitted = stereo_station(rig.left, rig.right);
  StereoStation station = unfitted;
  const StereoOptions range = fit_disparity_range(station, platter_radius, 60.0);
  EXPECT_EQ(range.num_disparities % 16, 0);
  EXPECT_EQ(range.min_disparity, 0);
  // The copy it started from is untouched (cv::Mat shares its data).
  EXPECT_NE(unfitted.calibration.q.at<double>(3, 3), station.calibration.q.at<double>(3, 3));
  EXPECT_GT(cv::norm(unfitted.right_map_x, station.right_map_x, cv::NORM_INF), 1.0);
  const cv::Matx34d P1 = station.calibration.p1, P2 = station.calibration.p2;
  sim::Random random(3);
  int inside = 0;
  for (int i = 0; i < 500; ++i) {
    const double r = platter_radius * std::sqrt(random.uniform()), phi = random.uniform(0, 2 * std::numbers::pi);
    const Eigen::Vector3d p{r * std::cos(phi), r * std::sin(phi), random.uniform(0, 60)};
    // Each camera's distorted pixel, rectified by the maps, is the rectified projection.
    const Eigen::Vector3d rect = eigen33(station.calibration.r1) * (rig.left.rotation * p + rig.left.translation);
    const cv::Vec3d l = P1 * cv::Vec4d(rect.x(), rect.y(), rect.z(), 1), rr = P2 * cv::Vec4d(rect.x(), rect.y(), rect.z(), 1);
    const double d = l[0] / l[2] - rr[0] / rr[2];
    EXPECT_GE(d, 4.0);  // the margin
    EXPECT_LT(d, range.num_disparities - 4.0);
    // The rectification maps send the rectified projection back to each
    // camera's own (distorted) pixel, on the same row of both views.
    const cv::Point2f at(static_cast<float>(l[0] / l[2]), static_cast<float>(l[1] / l[2]));
    const cv::Point2f in_right(at.x - static_cast<float>(d), at.y);
    if (in_right.x < 1 || at.y < 1 || at.x > 318 || at.y > 238) continue;
    for (const auto& [camera, rectified, map_x, map_y] :
         {std::tuple{&rig.left, at, station.left_map_x, station.left_map_y},
          std::tuple{&rig.right, in_right, station.right_map_x, station.right_map_y}}) {
      cv::Mat x, y;
      cv::getRectSubPix(map_x, {1, 1}, rectified, x);
      cv::getRectSubPix(map_y, {1, 1}, rectified, y);
      const auto pixel = camera->project(p);
      ASSERT_TRUE(pixel);
      EXPECT_NEAR(x.at<float>(0, 0), pixel->x(), 0.01);
      EXPECT_NEAR(y.at<float>(0, 0), pixel->y(), 0.01);
    }
    ++inside;
  }
  EXPECT_GT(inside, 300);
}

// Per-view points and their fusion for a texture-less object at `views`
// turntable angles.
struct StereoScan {
  std::vector<LaserScanPoints> views;
  LaserScanPoints fused;
};

StereoScan stereo_scan(const TriangleMesh& object, double object_height, int views, bool projector) {
  const sim::StereoRig rig = sim::stereo_rig(object_height, platter_radius, 640, 480);
  const sim::SceneRenderer renderer(sim::stereo_scene(object, rig, platter_radius, projector));
  StereoStation station = stereo_station(rig.left, rig.right);
  StereoReconstructionOptions options;
  options.matcher = fit_disparity_range(station, platter_radius, object_height, options.matcher);
  // The object's own cylinder: beyond it lie the platter's far rim and the
  // void, where SGBM spreads the rim's texture.
  options.maximum_radius = object.vertices.positions.leftCols(2).rowwise().norm().maxCoeff() + 2.0;
  StereoScan scan;
  for (int v = 0; v < views; ++v) {
    const double angle = 2.0 * std::numbers::pi * v / views;
    const cv::Mat left = renderer.expose(renderer.cast(rig.left, angle), {}, 2 * static_cast<std::uint64_t>(v));
    const cv::Mat right = renderer.expose(renderer.cast(rig.right, angle), {}, 2 * static_cast<std::uint64_t>(v) + 1);
    scan.views.push_back(stereo_view_points(station, left, right, angle, options));
  }
  FusionOptions fusion;
  fusion.voxel = 0.5;
  fusion.minimum_views = 2;
  fusion.outlier_radius = 1.5;
  scan.fused = fuse_views(scan.views, fusion);
  return scan;
}

double diagonal(const TriangleMesh& mesh) {
  return (mesh.vertices.positions.colwise().maxCoeff() - mesh.vertices.positions.colwise().minCoeff()).norm();
}

template <class Distance>
double rms_distance(const Eigen::MatrixX3d& P, Distance distance) {
  double squared = 0;
  for (Eigen::Index i = 0; i < P.rows(); ++i) squared += std::pow(distance(P.row(i).transpose()), 2);
  return std::sqrt(squared / static_cast<double>(P.rows()));
}

// Budget: fused RMS distance to the true surface ≤ 0.3% of the bounding-box
// diagonal (the stereo depth step at this baseline is about 1.2 mm per pixel
// of disparity, 1% of the diagonal; SGBM's sub-pixel disparities and the
// merging of views bring it down); coverage of the true surface ≥ 75% (the
// underside and the parts facing the platter stay hidden).
TEST(StereoReconstruction, FusedViewsOfTextureLessObjectsMatchTheirSurfaces) {
  constexpr double radius = 30.0;
  const Eigen::Vector3d centre{6.0, -4.0, radius};
  TriangleMesh sphere = sim::ellipsoid(Eigen::Vector3d::Constant(radius), 6);
  sphere.vertices.positions.rowwise() += centre.transpose();
  // A ring standing on its edge, off the axis: a hole, self-occlusion, and no
  // symmetry about the turntable axis, so a wrong rotation would show.
  constexpr double R = 24.0, r = 8.0;
  const Eigen::Vector3d ring_centre{5.0, 3.0, R + r};
  const Eigen::Matrix3d upright = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  TriangleMesh ring = sim::torus(R, r, 256, 96);
  ring.vertices.positions = (ring.vertices.positions * upright.transpose()).rowwise() + ring_centre.transpose();

  const auto sphere_distance = [&](const Eigen::Vector3d& p) { return (p - centre).norm() - radius; };
  const auto ring_distance = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = upright.transpose() * (p - ring_centre);
    return std::hypot(q.head<2>().norm() - R, q.z()) - r;
  };
  struct Case {
    const char* name;
    const TriangleMesh& mesh;
    double height;
    std::function<double(const Eigen::Vector3d&)> distance;
  };
  for (const Case& c : {Case{"sphere", sphere, 2 * radius, sphere_distance}, Case{"ring", ring, 2 * (R + r), ring_distance}}) {
    const StereoScan scan = stereo_scan(c.mesh, c.height, 8, true);
    const Eigen::MatrixX3d& P = scan.fused.cloud.positions;
    Eigen::Index raw = 0;
    double raw_squared = 0;
    for (const LaserScanPoints& v : scan.views) {
      raw += v.cloud.size();
      raw_squared += std::pow(rms_distance(v.cloud.positions, c.distance), 2) * static_cast<double>(v.cloud.size());
    }
    ASSERT_GT(P.rows(), 10000) << c.name;
    const double rms = rms_distance(P, c.distance), raw_rms = std::sqrt(raw_squared / static_cast<double>(raw));
    const double d = diagonal(c.mesh);
    const double covered = coverage(sim::sample_surface(c.mesh, 4000, 9).positions, P, 0.02 * d);
    std::printf("%s: %ld points in 8 views (RMS %.3f mm), %ld fused, RMS %.3f mm = %.3f%% of the diagonal, coverage %.1f%%\n",
                c.name, static_cast<long>(raw), raw_rms, static_cast<long>(P.rows()), rms, 100 * rms / d, 100 * covered);
    RecordProperty(std::string(c.name) + "_rms_mm", std::to_string(rms));
    EXPECT_LE(rms, 3e-3 * d) << c.name;
    EXPECT_LT(rms, raw_rms) << c.name;  // fusion helps
    EXPECT_GT(covered, 0.75) << c.name;
    EXPECT_EQ(scan.fused.confidence.size(), static_cast<std::size_t>(P.rows()));
    EXPECT_EQ(scan.fused.cloud.colors.rows(), P.rows());
  }
}

// Without the projector the object's smooth shading gives the matcher too
// little to go on: most of it has no points. With it, the object is covered.
TEST(StereoReconstruction, TheDotProjectorGivesTextureLessObjectsPoints) {
  TriangleMesh sphere = sim::icosphere(5);
  sphere.vertices.positions *= 30.0;
  sphere.vertices.positions.col(2).array() += 30.0;
  const StereoScan with = stereo_scan(sphere, 60.0, 1, true), without = stereo_scan(sphere, 60.0, 1, false);
  const Eigen::Index on = with.views[0].cloud.size(), off = without.views[0].cloud.size();
  std::printf("one view of a white sphere: %ld points with the projector, %ld without\n", static_cast<long>(on),
              static_cast<long>(off));
  EXPECT_GT(on, 20000);
  EXPECT_GT(on, 5 * off);
}

TEST(StereoReconstruction, ColoursFromAFrameWithoutTheDots) {
  const sim::StereoRig rig = sim::stereo_rig(60.0, platter_radius, 160, 120);
  const StereoStation station = stereo_station(rig.left, rig.right);
  cv::Mat disparity(120, 160, CV_32F, cv::Scalar(40.0f));
  cv::Mat texture(120, 160, CV_8U);
  cv::randu(texture, 0, 255);
  const cv::Mat colour(120, 160, CV_8UC3, cv::Scalar(10, 20, 30));  // BGR
  StereoReconstructionOptions options;
  options.minimum_height = -std::numeric_limits<double>::infinity();
  LaserScanPoints points;
  disparity_to_points(station, disparity, texture, 0.0, points, options, colour);
  ASSERT_GT(points.cloud.size(), 1000);
  EXPECT_EQ(points.cloud.colors.col(0).cast<int>().minCoeff(), 30);  // RGB
  EXPECT_EQ(points.cloud.colors.col(2).cast<int>().maxCoeff(), 10);
  test::expect_error<InvalidInput>(
      [&] { disparity_to_points(station, disparity, texture, 0.0, points, options, colour(cv::Rect(0, 0, 9, 9))); },
      {"colour frame"});
}

TEST(ViewFusion, MergesAgreeingViewsAndDropsWhatOnlyOneViewSaw) {
  // Two views of the same 10 × 10 grid of points (jittered well inside their
  // cubes), the second with a stray point of its own.
  std::vector<LaserScanPoints> views(2);
  sim::Random random(5);
  for (std::size_t v = 0; v < 2; ++v) {
    const Eigen::Index n = v == 0 ? 100 : 101;
    views[v].cloud.positions.resize(n, 3);
    views[v].cloud.colors.resize(n, 3);
    for (Eigen::Index i = 0; i < 100; ++i) {
      views[v].cloud.positions.row(i) << (i % 10) + 0.5 + 0.1 * random.normal() * 0.5, (i / 10) + 0.5, 0.5;
      views[v].cloud.colors.row(i).setConstant(v == 0 ? 100 : 200);
      views[v].confidence.push_back(v == 0 ? 0.25 : 0.75);
    }
  }
  views[1].cloud.positions.row(100) << 50.5, 50.5, 50.5;
  views[1].cloud.colors.row(100).setConstant(0);
  views[1].confidence.push_back(0.5);

  FusionOptions options;
  options.voxel = 1.0;
  const LaserScanPoints all = fuse_views(views, options);
  ASSERT_EQ(all.cloud.size(), 101);
  // Confidence-weighted: a quarter of the first view, three quarters of the second.
  EXPECT_NEAR(all.cloud.positions(0, 0),
              0.25 * views[0].cloud.positions(0, 0) + 0.75 * views[1].cloud.positions(0, 0), 1e-12);
  EXPECT_EQ(all.cloud.colors(0, 0), 175);
  EXPECT_NEAR(all.confidence[0], 1 - 0.75 * 0.25, 1e-12);
  EXPECT_EQ(all.cloud.positions(100, 0), 50.5);

  options.minimum_views = 2;
  EXPECT_EQ(fuse_views(views, options).cloud.size(), 100);
  options.minimum_views = 1;
  options.outlier_radius = 1.5;
  options.min_neighbours = 2;
  const LaserScanPoints cleaned = fuse_views(views, options);
  EXPECT_EQ(cleaned.cloud.size(), 100);
  EXPECT_EQ(cleaned.confidence.size(), 100u);
  // Same input, same bytes.
  EXPECT_EQ(fuse_views(views, options).cloud.positions, cleaned.cloud.positions);

  options.voxel = 0;
  test::expect_error<InvalidInput>([&] { fuse_views(views, options); }, {"voxel"});
  options.voxel = 1.0;
  views[1].confidence.pop_back();
  test::expect_error<InvalidInput>([&] { fuse_views(views, options); }, {"view 1"});
}

}  // namespace
}  // namespace scanstation::acquisition
