#include "sim/turntable_rig.h"

#include "core/errors.h"

#include <cmath>

namespace scanstation::sim {

RigViewpoint rig_viewpoint(double object_height, double platter_radius, double distance_factor, double margin) {
  RigViewpoint view;
  view.distance = distance_factor * std::max(object_height, platter_radius);
  view.target = Point3{0, 0, 0.5 * object_height};
  view.eye = Point3{0, -view.distance, 0.5 * object_height + 0.35 * view.distance};
  const double half_extent = margin * std::max(platter_radius, 0.75 * object_height);
  view.fov = 2.0 * std::atan(half_extent / view.distance);
  return view;
}

TurntableLaserRig turntable_laser_rig(double object_height, double platter_radius, int width, int height,
                                      double laser_angle) {
  if (!(object_height > 0) || !(platter_radius > 0))
    throw InvalidInput("turntable rig: object height and platter radius must be positive");
  const RigViewpoint view = rig_viewpoint(object_height, platter_radius, 4.0, 1.15);
  const double distance = view.distance;
  const Point3& target = view.target;
  TurntableLaserRig rig;
  rig.camera = PinholeCamera::look_at(view.eye, target, Eigen::Vector3d::UnitZ(), width, height, view.fov);
  rig.camera.distortion = {-0.08, 0.03, 0.0, 0.0004, -0.0003};
  const double beam_sigma = 0.8 * distance / rig.camera.fx;  // about 0.8 px at the axis
  for (const double side : {-1.0, 1.0}) {
    LineLaser laser;
    const Eigen::Vector3d emitter = turntable_rotation(side * laser_angle) * Eigen::Vector3d(0, -distance, target.z());
    laser.plane.origin = emitter;
    laser.plane.normal = Eigen::Vector3d::UnitZ().cross(emitter).normalized();
    laser.beam_sigma = beam_sigma;
    rig.lasers.push_back(laser);
  }
  return rig;
}

Scene turntable_scene(TriangleMesh object, const TurntableLaserRig& rig, double platter_radius) {
  Scene scene;
  scene.object = std::move(object);
  scene.platter_radius = platter_radius;
  scene.lasers = rig.lasers;
  return scene;
}

}  // namespace scanstation::sim
