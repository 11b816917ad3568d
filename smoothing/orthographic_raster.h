// Software rendering of triangle meshes for pictures people look at (the
// reflection lines of §8.4, the station's preview): an orthographic view
// fitted to a point set, and z-buffered rasterisation that hands every
// visible pixel's normal to a painter.
#pragma once

#include "core/triangle_mesh.h"

#include <Eigen/Core>
#include <functional>

namespace scanstation {

/// Looking along −forward; right and up span the image (y down in pixels).
struct OrthographicView {
  Eigen::Matrix3d rows;  ///< right, up, forward (towards the eye)
  Eigen::Vector3d centre;
  double pixels_per_unit = 1.0;
  int width = 0, height = 0;

  /// Pixel x, y and the depth along forward (larger is nearer).
  Eigen::Vector3d to_screen(const Eigen::Vector3d& p) const;
};

/// The view from `forward` (towards the eye, any length), the image's up as
/// close to `up` as possible, whose image of `positions` (#P by 3) is
/// centred and fills `fill` of the smaller side of a width × height image.
OrthographicView fitted_view(const Eigen::MatrixX3d& positions, const Eigen::Vector3d& forward, int width, int height,
                             const Eigen::Vector3d& up = Eigen::Vector3d::UnitY(), double fill = 0.9);

/// Paints the visible surface of `mesh`: `paint(x, y, n)` for every pixel
/// whose centre is covered by the nearest triangle, n the unit normal in view
/// coordinates (x right, y up, z towards the eye) — interpolated from the
/// vertex normals when `interpolate_normals` and the mesh has them, else the
/// face normal. A pixel may be painted again by a nearer triangle.
void rasterize(const TriangleMesh& mesh, bool interpolate_normals, const OrthographicView& view,
               const std::function<void(int x, int y, const Eigen::Vector3d& n)>& paint);

}  // namespace scanstation
