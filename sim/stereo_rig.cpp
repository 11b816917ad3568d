#include "sim/stereo_rig.h"

#include "core/errors.h"
#include "sim/turntable_rig.h"

#include <cmath>

namespace scanstation::sim {

StereoRig stereo_rig(double object_height, double platter_radius, int width, int height, double baseline) {
  if (!(object_height > 0) || !(platter_radius > 0) || !(baseline > 0) || width <= 0 || height <= 0)
    throw InvalidInput("stereo rig: object height, platter radius, baseline and image size must be positive");
  // The turntable rig's view, a little closer: stereo depth resolution falls
  // with the square of the distance.
  const RigViewpoint view = rig_viewpoint(object_height, platter_radius, 3.0, 1.1);
  const double distance = view.distance, fov = view.fov;
  const Point3 &eye = view.eye, &target = view.target;
  const Eigen::Vector3d side = 0.5 * baseline * distance * Eigen::Vector3d::UnitX();
  StereoRig rig;
  rig.left = PinholeCamera::look_at(eye - side, target, Eigen::Vector3d::UnitZ(), width, height, fov);
  rig.left.distortion = {-0.06, 0.02, 0.0, 0.0003, -0.0002};
  rig.right = PinholeCamera::look_at(eye + side, target, Eigen::Vector3d::UnitZ(), width, height, fov);
  rig.right.distortion = {-0.07, 0.025, 0.0, -0.0002, 0.0004};
  // Cells of about two camera pixels: fine enough for a 5-pixel matching
  // block to hold several, coarse enough to survive the defocus.
  constexpr double cell_pixels = 2.0;
  const double projector_fov = 1.15 * fov;
  const int projector_width = static_cast<int>(std::lround(width * projector_fov / fov / cell_pixels));
  const int projector_height = static_cast<int>(std::lround(height * projector_fov / fov / cell_pixels));
  rig.projector.optics =
      PinholeCamera::look_at(eye, target, Eigen::Vector3d::UnitZ(), projector_width, projector_height, projector_fov);
  return rig;
}

Scene stereo_scene(TriangleMesh object, const StereoRig& rig, double platter_radius, bool with_projector) {
  Scene scene;
  scene.object = std::move(object);
  scene.platter_radius = platter_radius;
  if (with_projector) scene.projector = rig.projector;
  return scene;
}

}  // namespace scanstation::sim
