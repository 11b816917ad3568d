#include "smoothing/orthographic_raster.h"

#include "core/unit_scale.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace scanstation {

Eigen::Vector3d OrthographicView::to_screen(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d c = rows * (p - centre);
  return {width / 2.0 + c.x() * pixels_per_unit, height / 2.0 - c.y() * pixels_per_unit, c.z()};
}

OrthographicView fitted_view(const Eigen::MatrixX3d& positions, const Eigen::Vector3d& forward_in, int width,
                             int height, const Eigen::Vector3d& up_hint, double fill) {
  const Eigen::Vector3d forward = forward_in.normalized();
  Eigen::Vector3d right = up_hint.cross(forward);
  if (right.norm() < 1e-9 * up_hint.norm()) right = forward.unitOrthogonal();  // looking straight along up
  right.normalize();
  const Eigen::Vector3d up = forward.cross(right);
  OrthographicView view;
  view.rows << right.transpose(), up.transpose(), forward.transpose();
  view.centre = positions.rows() == 0
                    ? Eigen::Vector3d::Zero()
                    : Eigen::Vector3d((positions.colwise().minCoeff() + positions.colwise().maxCoeff()).transpose() / 2.0);
  double extent = 0.0;
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    const Eigen::Vector3d c = view.rows * (Eigen::Vector3d(positions.row(i)) - view.centre);
    extent = std::max({extent, std::abs(c.x()), std::abs(c.y())});
  }
  view.pixels_per_unit = fill / 2.0 * std::min(width, height) / std::max(extent, std::numeric_limits<double>::min());
  view.width = width;
  view.height = height;
  return view;
}

void rasterize(const TriangleMesh& mesh, bool interpolate_normals, const OrthographicView& view,
               const std::function<void(int x, int y, const Eigen::Vector3d& n)>& paint) {
  std::vector<double> depth(static_cast<std::size_t>(view.width) * view.height,
                            -std::numeric_limits<double>::infinity());
  const auto& P = mesh.vertices.positions;
  const bool smooth = interpolate_normals && mesh.vertices.has_normals();
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    Eigen::Vector3d p[3], n[3];
    for (int c = 0; c < 3; ++c) p[c] = view.to_screen(P.row(mesh.faces(f, c)));
    const Eigen::Vector3d a = P.row(mesh.faces(f, 0)), b = P.row(mesh.faces(f, 1)), c2 = P.row(mesh.faces(f, 2));
    const Eigen::Vector3d face = (view.rows * scaled_cross(b - a, c2 - a)).normalized();
    for (int c = 0; c < 3; ++c)
      n[c] = smooth ? Eigen::Vector3d(view.rows * mesh.vertices.normals.row(mesh.faces(f, c)).transpose()) : face;
    const double area = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[2].x() - p[0].x()) * (p[1].y() - p[0].y());
    if (area == 0.0 || !std::isfinite(area)) continue;
    const int xmin = std::max(0, int(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int xmax = std::min(view.width - 1, int(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int ymin = std::max(0, int(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int ymax = std::min(view.height - 1, int(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = ymin; y <= ymax; ++y)
      for (int x = xmin; x <= xmax; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        const double w0 = ((p[1].x() - px) * (p[2].y() - py) - (p[2].x() - px) * (p[1].y() - py)) / area;
        const double w1 = ((p[2].x() - px) * (p[0].y() - py) - (p[0].x() - px) * (p[2].y() - py)) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double z = w0 * p[0].z() + w1 * p[1].z() + w2 * p[2].z();
        double& stored = depth[static_cast<std::size_t>(y) * view.width + x];
        if (z <= stored) continue;
        stored = z;
        paint(x, y, (w0 * n[0] + w1 * n[1] + w2 * n[2]).normalized());
      }
  }
}

}  // namespace scanstation
