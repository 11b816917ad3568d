// Reflection lines (zebra stripes of parallel linear light sources, thesis
// §8.4) rendered in software: continuity of a surface judged by eye.
#pragma once

#include "core/io/file_access.h"
#include "core/triangle_mesh.h"

#include <filesystem>
#include <string>

namespace scanstation {

/// width_px, height_px  size of each of the two views; stripes  light lines
/// across the reflected half-sphere.
struct ReflectionLineOptions {
  int width_px = 640;
  int height_px = 640;
  double stripes = 7.0;
};

/// Renders `smooth` (per-vertex normals interpolated per pixel; if it has
/// none, face normals) on the left and `flat` (always face normals) on the
/// right, seen orthographically from the same oblique direction, each pixel
/// black or white by the reflected direction's angle around the light lines'
/// axis, shaded by n·view. A G¹ surface shows continuous stripes that may
/// kink at patch edges (a G¹ reflection line needs G², §8.4); the polyhedron
/// shows stripes broken at every edge. Returns PNG bytes.
std::string reflection_lines_png(const TriangleMesh& smooth, const TriangleMesh& flat,
                                 const ReflectionLineOptions& options = {});

}  // namespace scanstation
