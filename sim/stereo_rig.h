// A simulated stereo rig sized for an object on the turntable: two cameras
// side by side, converging on the object, and a random-dot projector between
// them that gives texture-less objects a texture to match.
#pragma once

#include "sim/scene_renderer.h"

namespace scanstation::sim {

/// left, right  cameras `baseline` apart along the station's x axis, both
///              looking at the middle of the object from in front (−y) and
///              slightly above, each with its own mild lens distortion
/// projector    midway between them, looking at the same point, its field a
///              little wider than the cameras' and its cells about two
///              camera pixels wide on the object
struct StereoRig {
  PinholeCamera left, right;
  DotProjector projector;
};

/// A rig for an object of height `object_height` (station units) on a platter
/// of radius `platter_radius`, with width × height cameras whose field of
/// view frames the platter; `baseline` is a fraction of the viewing distance.
/// Throws InvalidInput for non-positive sizes.
StereoRig stereo_rig(double object_height, double platter_radius, int width, int height, double baseline = 0.2);

/// A scene for the rig: the object on the platter, the projector when
/// `with_projector`, no lasers.
Scene stereo_scene(TriangleMesh object, const StereoRig& rig, double platter_radius, bool with_projector = true);

}  // namespace scanstation::sim
