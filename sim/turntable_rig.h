// A simulated turntable laser rig sized for an object: one camera and two
// line lasers, the typical layout of desktop turntable scanners.
#pragma once

#include "sim/scene_renderer.h"

namespace scanstation::sim {

/// camera  looks at the middle of the object from `distance` in front (−y),
///         slightly from above, with a mild barrel distortion
/// lasers  two vertical light planes through the turntable axis, their
///         emitters at ±`laser_angle` (radians) beside the camera
struct TurntableLaserRig {
  PinholeCamera camera;
  std::vector<LineLaser> lasers;
};

/// Where a rig's camera stands: `distance_factor` × max(object height,
/// platter radius) in front of the object (−y), a little above it, looking at
/// its middle, with a horizontal field of view that frames the platter and
/// the object's height, whichever needs more, with `margin` (1.1 = 10%) around.
struct RigViewpoint {
  Point3 eye, target;
  double distance = 0, fov = 0;
};
RigViewpoint rig_viewpoint(double object_height, double platter_radius, double distance_factor, double margin);

/// A rig for an object of height `object_height` (station units) on a platter
/// of radius `platter_radius`, with a width × height camera whose field of
/// view frames the platter.
TurntableLaserRig turntable_laser_rig(double object_height, double platter_radius, int width, int height,
                                      double laser_angle = 0.5);

/// A scene for the rig: the object on the platter, the rig's lasers.
Scene turntable_scene(TriangleMesh object, const TurntableLaserRig& rig, double platter_radius);

}  // namespace scanstation::sim
