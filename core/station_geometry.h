// The geometry of a scanning station, shared by the simulator and the
// acquisition pipelines.
//
// Station frame: z is the turntable axis pointing up, the origin is the centre
// of the platter's top surface. The object frame turns with the platter: a point
// p of the object is at turntable_rotation(angle) · p in the station frame.
#pragma once

#include "core/point_cloud.h"

#include <Eigen/Geometry>
#include <cmath>
#include <optional>

namespace scanstation {

/// Rotation of the platter by `angle` radians about the station's z axis
/// (counter-clockwise seen from above): object frame → station frame.
inline Eigen::Matrix3d turntable_rotation(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// Brown–Conrady lens distortion in OpenCV's convention (k1, k2, p1, p2, k3)
/// on normalised image coordinates.
struct BrownConrady {
  double k1 = 0, k2 = 0, k3 = 0, p1 = 0, p2 = 0;

  Eigen::Vector2d distort(const Eigen::Vector2d& x) const {
    const double r2 = x.squaredNorm();
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double xy = x.x() * x.y();
    return {x.x() * radial + 2.0 * p1 * xy + p2 * (r2 + 2.0 * x.x() * x.x()),
            x.y() * radial + p1 * (r2 + 2.0 * x.y() * x.y()) + 2.0 * p2 * xy};
  }

  /// Inverse of distort by fixed-point iteration (OpenCV's scheme, iterated
  /// to convergence): exact to ~1e-15 for the mild distortion of real lenses.
  Eigen::Vector2d undistort(const Eigen::Vector2d& distorted) const {
    Eigen::Vector2d x = distorted;
    for (int iteration = 0; iteration < 100; ++iteration) {
      const double r2 = x.squaredNorm();
      const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
      const double xy = x.x() * x.y();
      const Eigen::Vector2d tangential{2.0 * p1 * xy + p2 * (r2 + 2.0 * x.x() * x.x()),
                                       p1 * (r2 + 2.0 * x.y() * x.y()) + 2.0 * p2 * xy};
      const Eigen::Vector2d next = (distorted - tangential) / radial;
      if ((next - x).squaredNorm() < 1e-28) return next;  // 1e-14: far below a pixel's 1e-3
      x = next;
    }
    return x;
  }
};

/// A pinhole camera with lens distortion and its pose in the station frame.
/// x_camera = rotation · x_station + translation; the camera looks along +z,
/// image x to the right, image y down; pixel centres at integer coordinates.
struct PinholeCamera {
  int width = 640, height = 480;
  double fx = 1000, fy = 1000, cx = 319.5, cy = 239.5;
  BrownConrady distortion;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d centre() const { return -rotation.transpose() * translation; }

  /// Pixel of a station point, or nothing for a point behind the camera.
  std::optional<Eigen::Vector2d> project(const Point3& station) const {
    const Eigen::Vector3d c = rotation * station + translation;
    if (!(c.z() > 0)) return std::nullopt;
    const Eigen::Vector2d d = distortion.distort(c.head<2>() / c.z());
    return Eigen::Vector2d{fx * d.x() + cx, fy * d.y() + cy};
  }

  /// Unit direction, in the station frame, of the ray through a pixel.
  Eigen::Vector3d ray_direction(const Eigen::Vector2d& pixel) const {
    const Eigen::Vector2d x = distortion.undistort({(pixel.x() - cx) / fx, (pixel.y() - cy) / fy});
    return (rotation.transpose() * Eigen::Vector3d(x.x(), x.y(), 1.0)).normalized();
  }

  /// A distortion-free camera at `eye` looking at `target`, with `up` pointing
  /// up in the image and the given horizontal field of view (radians).
  static PinholeCamera look_at(const Point3& eye, const Point3& target, const Eigen::Vector3d& up, int width,
                               int height, double horizontal_fov) {
    PinholeCamera camera;
    camera.width = width;
    camera.height = height;
    camera.fx = camera.fy = 0.5 * width / std::tan(0.5 * horizontal_fov);
    camera.cx = 0.5 * (width - 1);
    camera.cy = 0.5 * (height - 1);
    const Eigen::Vector3d z = (target - eye).normalized();
    const Eigen::Vector3d x = z.cross(up).normalized();
    const Eigen::Vector3d y = z.cross(x);
    camera.rotation.row(0) = x;
    camera.rotation.row(1) = y;
    camera.rotation.row(2) = z;
    camera.translation = -camera.rotation * eye;
    return camera;
  }
};

/// The light plane of a line laser in the station frame: it contains `origin`
/// (the emitter) and has unit `normal`.
struct LaserPlane {
  Point3 origin = Point3::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();

  double signed_distance(const Point3& p) const { return normal.dot(p - origin); }
};

}  // namespace scanstation
