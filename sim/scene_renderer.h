// A ray-cast turntable scene (Embree): a mesh object on a platter, line
// lasers, an optional random-dot projector, ambient and one directional room
// light, seen by pinhole cameras with
// lens distortion, with a sensor model (speckle, defocus, shot and read noise,
// 8-bit quantisation). Ground truth for every pixel.
//
// Geometry and lighting are cast once per (camera, turntable angle) into a
// RenderedView; any number of frames (laser on/off, different seeds) are then
// exposed from it, so a laser-on/laser-off pair costs one ray cast.
#pragma once

#include "core/station_geometry.h"
#include "core/triangle_mesh.h"

#include <opencv2/core.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace scanstation::sim {

/// A line laser: its light plane, a Gaussian beam profile across the plane
/// (standard deviation in station units) and its irradiance on a surface
/// facing it (in grey levels for albedo 1).
struct LineLaser {
  LaserPlane plane;
  double beam_sigma = 0.25;
  double power = 400.0;
  double speckle_contrast = 0.05;  // standard deviation of the multiplicative speckle
};

/// A random-dot projector (the active texture of stereo rigs): a pinhole
/// projector casting a seeded pattern of lit and dark cells, one per
/// projector pixel, onto the scene, shadowed by the object, so that
/// texture-less surfaces give a stereo matcher something to match.
/// optics  pose, field, resolution and lens of the projector; its image is
///         the pattern
/// power   irradiance of a lit cell on a surface facing it (grey levels for albedo 1)
/// fill    fraction of lit cells
/// seed    the pattern: the same seed gives the same dots on every machine
struct DotProjector {
  PinholeCamera optics;
  double power = 110.0;
  double fill = 0.5;
  std::uint64_t seed = 1;
};

/// Surface reflectance: Lambertian albedo plus a Blinn–Phong lobe.
struct Material {
  double albedo = 0.7;
  double specular = 0.15;
  double shininess = 40.0;
};

/// Sensor model, in grey levels (0..255 after quantisation).
struct SensorModel {
  double electrons_per_level = 40.0;  // shot noise: variance = signal / electrons_per_level
  double read_noise = 0.8;            // grey levels, Gaussian
  double defocus_sigma = 0.6;         // pixels, Gaussian blur before the noise
  bool noise = true;                  // false: an exact, noise-free rendering (still blurred and quantised)
};

/// A chessboard calibration target standing on the platter (it turns with
/// it): inner corner (0, 0) at `origin` (object frame), columns along unit
/// `across`, rows along unit `down`; (inner_corners + 1) squares each way
/// and a white margin of one square. It casts no shadows.
struct ChessboardTarget {
  Point3 origin = Point3::Zero();
  Eigen::Vector3d across = Eigen::Vector3d::UnitX(), down = -Eigen::Vector3d::UnitZ();
  int columns = 9, rows = 6;  // inner corners
  double square = 5.0;
  double black = 0.05, white = 0.85;  // albedos

  /// The station-independent object-frame position of inner corner (c, r).
  Point3 corner(int c, int r) const { return origin + square * (c * across + r * down); }
};

/// The scene in the station frame (see core/station_geometry.h): the object's
/// mesh is given in the object frame, standing on the platter (z ≥ 0); it may
/// be empty when a board is shown.
struct Scene {
  TriangleMesh object;
  Material object_material;
  double platter_radius = 120.0;
  Material platter_material{0.25, 0.02, 10.0};
  std::vector<LineLaser> lasers;
  std::optional<ChessboardTarget> board;
  std::optional<DotProjector> projector;
  double ambient = 40.0;                                     // grey levels for albedo 1
  Eigen::Vector3d light_direction{0.3, -0.5, 1.0};           // towards the room light
  double light_intensity = 90.0;                             // grey levels for albedo 1
};

/// What a pixel's ray hits.
enum class HitKind : std::uint8_t { none = 0, object = 1, platter = 2, board = 3 };

/// Per-pixel ground truth of one view (all images height × width).
/// kind       CV_8U, a HitKind
/// points     CV_64FC3, hit point in the object frame (0 where no hit)
/// depth      CV_64F, z of the hit in the camera frame (0 where no hit)
struct GroundTruth {
  cv::Mat kind, points, depth;
};

/// A cast view: ground truth and the noise-free radiance layers.
/// unlit      CV_32F, ambient + room light, in grey levels
/// laser      one CV_32F per laser: its light reflected to the camera (0 in
///            its shadow or where the camera does not see its spot)
/// dots       CV_32F, the projector's pattern reflected to the camera (empty
///            without a projector)
struct RenderedView {
  GroundTruth truth;
  cv::Mat unlit;
  std::vector<cv::Mat> laser;
  cv::Mat dots;
};

class SceneRenderer {
 public:
  explicit SceneRenderer(Scene scene);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  const Scene& scene() const;

  /// Casts one ray per pixel centre through the distorted lens with the
  /// platter turned by `turntable_angle`; shadow rays decide which laser spots
  /// are lit (seen from the laser origin AND the camera).
  RenderedView cast(const PinholeCamera& camera, double turntable_angle) const;

  /// An 8-bit grey frame (CV_8U) of a cast view with the lasers whose index is
  /// in `lasers_on` switched on. Speckle is fixed per view and laser (a
  /// property of the surface and the optics), the sensor noise comes from
  /// `seed`: same view, lasers and seed → the same bytes. The dot projector
  /// (if the scene has one) shines when `projector_on`.
  cv::Mat expose(const RenderedView& view, const std::vector<int>& lasers_on, std::uint64_t seed,
                 const SensorModel& sensor = {}, bool projector_on = true) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace scanstation::sim
