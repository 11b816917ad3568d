// All Embree use of the project lives in this file.
#include "sim/scene_renderer.h"

#include "core/errors.h"
#include "sim/random.h"

#include <embree3/rtcore.h>
#include <opencv2/imgproc.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace scanstation::sim {

namespace {

constexpr float infinity = std::numeric_limits<float>::infinity();

// Ray–triangle intersection in double (Möller–Trumbore) on the triangle
// Embree found: Embree works in float, the ground truth must lie on the mesh
// to double precision.
double refine_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const Eigen::Vector3d& a,
                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = direction.cross(e2);
  const double det = e1.dot(p);
  const Eigen::Vector3d s = origin - a;
  const Eigen::Vector3d q = s.cross(e1);
  return e2.dot(q) / det;
}

double blinn_phong(const Material& m, const Eigen::Vector3d& normal, const Eigen::Vector3d& to_light,
                   const Eigen::Vector3d& to_eye) {
  const double lambert = normal.dot(to_light);
  if (lambert <= 0) return 0.0;
  const Eigen::Vector3d half = (to_light + to_eye).normalized();
  return m.albedo * lambert + m.specular * std::pow(std::max(0.0, normal.dot(half)), m.shininess);
}

// Multiplicative speckle: 1 + contrast · (white noise blurred to a grain of
// about a pixel, rescaled to unit variance), never negative.
cv::Mat speckle_field(int rows, int cols, double contrast, std::uint64_t seed) {
  cv::Mat field(rows, cols, CV_32F);
  tbb::parallel_for(0, rows, [&](int r) {  // each row its own stream: the same field on any number of threads
    Random random(seed ^ (0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(r + 1)));
    auto* row = field.ptr<float>(r);
    for (int c = 0; c < cols; ++c) row[c] = static_cast<float>(random.normal());
  });
  constexpr double grain = 0.8;
  cv::GaussianBlur(field, field, cv::Size(0, 0), grain);
  // Variance of unit white noise after a Gaussian blur of σ: 1 / (4π σ²).
  const double scale = contrast * std::sqrt(4.0 * std::numbers::pi * grain * grain);
  field.convertTo(field, CV_32F, scale, 1.0);
  return cv::max(field, 0.0);
}

// Ray parameter and albedo where a ray meets the chessboard, or t = −1.
std::pair<double, double> board_hit(const ChessboardTarget& board, const Eigen::Vector3d& eye,
                                    const Eigen::Vector3d& direction) {
  const Eigen::Vector3d n = board.across.cross(board.down);
  const double facing = n.dot(direction);
  if (std::abs(facing) < 1e-12) return {-1.0, 0.0};
  const double t = n.dot(board.origin - eye) / facing;
  const Eigen::Vector3d q = eye + t * direction - board.origin;
  const double a = board.across.dot(q) / board.square, b = board.down.dot(q) / board.square;
  // Squares from −1 to columns (rows) in square units, one more of margin.
  if (!(t > 0) || a < -2 || a > board.columns + 1 || b < -2 || b > board.rows + 1) return {-1.0, 0.0};
  const bool on_squares = a >= -1 && a <= board.columns && b >= -1 && b <= board.rows;
  const bool dark = on_squares && (static_cast<long>(std::floor(a)) + static_cast<long>(std::floor(b))) % 2 == 0;
  return {t, dark ? board.black : board.white};
}

// The projector's pattern: one cell per projector pixel, 1 (lit) with
// probability `fill`, row by row from the seed.
cv::Mat random_dots(const DotProjector& projector) {
  if (projector.optics.width <= 0 || projector.optics.height <= 0 || !(projector.fill >= 0 && projector.fill <= 1))
    throw InvalidInput("scene renderer: the dot projector needs a positive resolution and a fill in [0, 1]");
  cv::Mat pattern(projector.optics.height, projector.optics.width, CV_8U);
  Random random(projector.seed);
  for (int r = 0; r < pattern.rows; ++r)
    for (int c = 0; c < pattern.cols; ++c) pattern.at<std::uint8_t>(r, c) = random.uniform() < projector.fill;
  return pattern;
}

}  // namespace

struct SceneRenderer::Impl {
  Scene scene;
  cv::Mat dot_pattern;  // of scene.projector, if any
  Eigen::MatrixX3d face_normals;
  RTCDevice device = nullptr;
  RTCScene rtc_scene = nullptr;

  // The station-frame ray through every pixel, per camera: a camera never
  // moves during a scan (the platter turns), and each pixel's ray takes a
  // fixed-point iteration to undistort, so a camera's rays are computed
  // once. A few cameras are kept (a stereo rig has two).
  struct CameraRays {
    PinholeCamera camera;
    std::shared_ptr<const std::vector<Eigen::Vector3d>> rays;
  };
  mutable std::mutex rays_mutex;
  mutable std::vector<CameraRays> known_rays;

  static bool same_rays(const PinholeCamera& a, const PinholeCamera& b) {
    const auto& p = a.distortion;
    const auto& q = b.distortion;
    return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy && a.cx == b.cx &&
           a.cy == b.cy && p.k1 == q.k1 && p.k2 == q.k2 && p.k3 == q.k3 && p.p1 == q.p1 && p.p2 == q.p2 &&
           a.rotation == b.rotation;
  }

  std::shared_ptr<const std::vector<Eigen::Vector3d>> rays_of(const PinholeCamera& camera) const {
    {
      const std::lock_guard lock(rays_mutex);
      for (const CameraRays& known : known_rays)
        if (same_rays(known.camera, camera)) return known.rays;
    }
    // Computed unlocked (a render may run inside another's parallel loop);
    // two threads may both compute one camera's rays, to the same values.
    auto rays = std::make_shared<std::vector<Eigen::Vector3d>>(static_cast<std::size_t>(camera.width) *
                                                               static_cast<std::size_t>(camera.height));
    tbb::parallel_for(0, camera.height, [&](int r) {
      for (int c = 0; c < camera.width; ++c)
        (*rays)[static_cast<std::size_t>(r) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(c)] =
            camera.ray_direction({c, r});
    });
    const std::lock_guard lock(rays_mutex);
    if (known_rays.size() == 4) known_rays.erase(known_rays.begin());
    known_rays.push_back({camera, rays});
    return rays;
  }

  explicit Impl(Scene s) : scene(std::move(s)) {
    const auto& V = scene.object.vertices.positions;
    const auto& F = scene.object.faces;
    if (F.rows() == 0 && !scene.board) throw InvalidInput("scene renderer: the object mesh has no triangles");
    if (F.rows() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
      throw InvalidInput("scene renderer: a triangle refers to a vertex that does not exist");
    face_normals.resize(F.rows(), 3);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const Eigen::Vector3d n = (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0)));
      face_normals.row(f) = n.norm() > 0 ? n.normalized() : Eigen::Vector3d::Zero();
    }
    for (auto& laser : scene.lasers) laser.plane.normal.normalize();
    scene.light_direction.normalize();
    if (scene.projector) dot_pattern = random_dots(*scene.projector);

    // No thread count for the device: Embree would apply it to all of the
    // process's TBB work (a tbb::global_control), and "threads=1" left the
    // whole station flow on one core. The BVH is built on one thread
    // instead (its own arena below), so it is the same on any machine.
    device = rtcNewDevice(nullptr);
    if (!device) throw SolverError("scene renderer: Embree could not create a device");
    rtc_scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(rtc_scene, RTC_BUILD_QUALITY_HIGH);
    if (F.rows() > 0) {  // a board-only scene has no mesh
      RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                   RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                   static_cast<std::size_t>(V.rows())));
      for (Eigen::Index v = 0; v < V.rows(); ++v)
        for (int k = 0; k < 3; ++k) vertices[3 * v + k] = static_cast<float>(V(v, k));
      auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                     RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                                     static_cast<std::size_t>(F.rows())));
      for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) indices[3 * f + k] = static_cast<unsigned>(F(f, k));
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(rtc_scene, geometry);
      rtcReleaseGeometry(geometry);
    }
    tbb::task_arena(1).execute([&] { rtcCommitScene(rtc_scene); });
  }

  ~Impl() {
    rtcReleaseScene(rtc_scene);
    rtcReleaseDevice(device);
  }

  // Nearest object triangle along a ray in the object frame: its index and the
  // ray parameter (double precision), or −1.
  std::pair<long, double> intersect_object(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query{};
    query.ray.org_x = static_cast<float>(origin.x());
    query.ray.org_y = static_cast<float>(origin.y());
    query.ray.org_z = static_cast<float>(origin.z());
    query.ray.dir_x = static_cast<float>(direction.x());
    query.ray.dir_y = static_cast<float>(direction.y());
    query.ray.dir_z = static_cast<float>(direction.z());
    query.ray.tnear = 0.0f;
    query.ray.tfar = infinity;
    query.ray.mask = 0xFFFFFFFFu;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtc_scene, &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {-1, 0.0};
    const long f = static_cast<long>(query.hit.primID);
    const auto& V = scene.object.vertices.positions;
    const auto& F = scene.object.faces;
    const double t = refine_hit(origin, direction, V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2)));
    return {f, t};
  }

  // Whether the open segment from `from` to `to` (object frame) crosses the object.
  bool occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double epsilon) const {
    const Eigen::Vector3d d = to - from;
    const double length = d.norm();
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = static_cast<float>(from.x());
    ray.org_y = static_cast<float>(from.y());
    ray.org_z = static_cast<float>(from.z());
    ray.dir_x = static_cast<float>(d.x() / length);
    ray.dir_y = static_cast<float>(d.y() / length);
    ray.dir_z = static_cast<float>(d.z() / length);
    ray.tnear = static_cast<float>(epsilon);
    ray.tfar = static_cast<float>(length - epsilon);
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(rtc_scene, &context, &ray);
    return ray.tfar < 0;
  }
};

SceneRenderer::SceneRenderer(Scene scene) : impl_(std::make_unique<Impl>(std::move(scene))) {}
SceneRenderer::~SceneRenderer() = default;
const Scene& SceneRenderer::scene() const { return impl_->scene; }

RenderedView SceneRenderer::cast(const PinholeCamera& camera, double turntable_angle) const {
  const Scene& scene = impl_->scene;
  const int rows = camera.height, cols = camera.width;
  if (rows <= 0 || cols <= 0) throw InvalidInput("scene renderer: the camera image must have a positive size");
  RenderedView view;
  view.truth.kind = cv::Mat::zeros(rows, cols, CV_8U);
  view.truth.points = cv::Mat::zeros(rows, cols, CV_64FC3);
  view.truth.depth = cv::Mat::zeros(rows, cols, CV_64F);
  view.unlit = cv::Mat::zeros(rows, cols, CV_32F);
  for (std::size_t l = 0; l < scene.lasers.size(); ++l) view.laser.push_back(cv::Mat::zeros(rows, cols, CV_32F));
  if (scene.projector) view.dots = cv::Mat::zeros(rows, cols, CV_32F);

  // Everything below happens in the object frame: the platter (a disc at z = 0
  // about the axis) is symmetric, so turning the camera, lights and lasers
  // by −angle is the same as turning the object by +angle.
  const Eigen::Matrix3d to_object = turntable_rotation(turntable_angle).transpose();
  const Eigen::Vector3d eye = to_object * camera.centre();
  const Eigen::Vector3d light = to_object * scene.light_direction;
  std::vector<LaserPlane> lasers;
  for (const auto& laser : scene.lasers)
    lasers.push_back({to_object * laser.plane.origin, to_object * laser.plane.normal});
  const Eigen::Vector3d projector_origin = scene.projector ? to_object * scene.projector->optics.centre() : eye;
  const double scale = std::max(1.0, (eye.norm()));
  const double epsilon = 1e-5 * scale;
  const Eigen::Matrix3d to_station = turntable_rotation(turntable_angle);
  const auto rays = impl_->rays_of(camera);

  tbb::parallel_for(0, rows, [&](int r) {
    for (int c = 0; c < cols; ++c) {
      const Eigen::Vector3d direction =
          to_object * (*rays)[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c)];
      auto [face, t] = impl_->intersect_object(eye, direction);
      Eigen::Vector3d normal;
      const Material* material = &scene.object_material;
      HitKind kind = HitKind::object;
      Material board_material{0, 0.02, 10.0};
      if (scene.board) {
        const auto [t_board, albedo] = board_hit(*scene.board, eye, direction);
        if (t_board > 0 && (face < 0 || !(t > 0) || t_board < t)) {
          face = -1;
          t = t_board;
          normal = scene.board->across.cross(scene.board->down).normalized();
          if (normal.dot(direction) > 0) normal = -normal;
          board_material.albedo = albedo;
          material = &board_material;
          kind = HitKind::board;
        }
      }
      if (kind != HitKind::board && (face < 0 || !(t > 0))) {
        const double t_platter = direction.z() < 0 ? -eye.z() / direction.z() : -1.0;
        const Eigen::Vector3d p = eye + t_platter * direction;
        if (!(t_platter > 0) || p.head<2>().norm() > scene.platter_radius) continue;
        t = t_platter;
        normal = Eigen::Vector3d::UnitZ();
        material = &scene.platter_material;
        kind = HitKind::platter;
      } else if (kind == HitKind::object) {
        normal = impl_->face_normals.row(face);
        if (normal.dot(direction) > 0) normal = -normal;  // seen from inside (open meshes)
      }
      const Eigen::Vector3d p = eye + t * direction;
      view.truth.kind.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(kind);
      view.truth.points.at<cv::Vec3d>(r, c) = {p.x(), p.y(), p.z()};
      view.truth.depth.at<double>(r, c) = (camera.rotation * (to_station * p) + camera.translation).z();
      const Eigen::Vector3d to_eye = -direction;
      const bool lit = !impl_->occluded(p, p + light * 4.0 * scale, epsilon);
      view.unlit.at<float>(r, c) = static_cast<float>(
          material->albedo * scene.ambient + (lit ? scene.light_intensity * blinn_phong(*material, normal, light, to_eye) : 0.0));
      for (std::size_t l = 0; l < lasers.size(); ++l) {
        const double d = lasers[l].signed_distance(p);
        const double sigma = scene.lasers[l].beam_sigma;
        if (std::abs(d) > 6.0 * sigma) continue;
        const Eigen::Vector3d to_laser = (lasers[l].origin - p).normalized();
        if (normal.dot(to_laser) <= 0 || impl_->occluded(p, lasers[l].origin, epsilon)) continue;
        const double beam = std::exp(-0.5 * d * d / (sigma * sigma));
        view.laser[l].at<float>(r, c) =
            static_cast<float>(scene.lasers[l].power * beam * blinn_phong(*material, normal, to_laser, to_eye));
      }
      if (scene.projector) {
        // The projector's light: the pattern cell the point sees from the
        // projector, unless the object shadows it.
        const auto cell = scene.projector->optics.project(to_station * p);
        if (!cell) continue;
        const int u = static_cast<int>(std::lround(cell->x())), v = static_cast<int>(std::lround(cell->y()));
        if (u < 0 || v < 0 || u >= impl_->dot_pattern.cols || v >= impl_->dot_pattern.rows ||
            !impl_->dot_pattern.at<std::uint8_t>(v, u))
          continue;
        const Eigen::Vector3d to_projector = (projector_origin - p).normalized();
        if (normal.dot(to_projector) <= 0 || impl_->occluded(p, projector_origin, epsilon)) continue;
        view.dots.at<float>(r, c) =
            static_cast<float>(scene.projector->power * blinn_phong(*material, normal, to_projector, to_eye));
      }
    }
  });

  const std::uint64_t view_seed = std::bit_cast<std::uint64_t>(turntable_angle) ^ 0xD1B54A32D192ED03ull;
  for (std::size_t l = 0; l < lasers.size(); ++l)
    if (scene.lasers[l].speckle_contrast > 0)
      view.laser[l] = view.laser[l].mul(speckle_field(rows, cols, scene.lasers[l].speckle_contrast, view_seed + l));
  return view;
}

cv::Mat SceneRenderer::expose(const RenderedView& view, const std::vector<int>& lasers_on, std::uint64_t seed,
                              const SensorModel& sensor, bool projector_on) const {
  cv::Mat radiance = view.unlit.clone();
  if (projector_on && !view.dots.empty()) radiance += view.dots;
  for (const int l : lasers_on) {
    if (l < 0 || static_cast<std::size_t>(l) >= view.laser.size())
      throw InvalidInput("scene renderer: there is no laser " + std::to_string(l));
    radiance += view.laser[static_cast<std::size_t>(l)];
  }
  if (sensor.defocus_sigma > 0) cv::GaussianBlur(radiance, radiance, cv::Size(0, 0), sensor.defocus_sigma);
  cv::Mat frame(radiance.rows, radiance.cols, CV_8U);
  // Shot and read noise are independent Gaussians, so their sum is one
  // Gaussian whose variance is the sum of theirs, and one polar step gives
  // two pixels their noise. (Drawing the two terms apart by Box–Muller, two
  // uniforms, a logarithm and a cosine each, took about half of a simulated
  // scan's time.)
  const double read_variance = sensor.read_noise * sensor.read_noise;
  const auto level = [&](double value, double normal) {
    if (sensor.noise) value += std::sqrt(std::max(0.0, value) / sensor.electrons_per_level + read_variance) * normal;
    return static_cast<std::uint8_t>(std::clamp(value, 0.0, 255.0) + 0.5);  // nearest, halves up (as lround on ≥ 0)
  };
  tbb::parallel_for(0, radiance.rows, [&](int r) {
    Random random(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(r));
    const float* in = radiance.ptr<float>(r);
    std::uint8_t* out = frame.ptr<std::uint8_t>(r);
    for (int c = 0; c < radiance.cols; c += 2) {
      const auto [first, second] = sensor.noise ? random.normal_pair() : std::pair{0.0, 0.0};
      out[c] = level(in[c], first);
      if (c + 1 < radiance.cols) out[c + 1] = level(in[c + 1], second);
    }
  });
  return frame;
}

}  // namespace scanstation::sim
