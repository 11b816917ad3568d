#include "smoothing/shaded_preview.h"

#include "core/errors.h"
#include "core/image_codecs.h"
#include "smoothing/orthographic_raster.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

namespace scanstation {

namespace {

// Lambert with a key light from the upper left and a weaker fill from the
// right, in view coordinates (x right, y up, z towards the eye).
// A flat face turned away is the inside showing (dark red); an interpolated
// normal may turn slightly away at a silhouette and is shaded as it is.
cv::Vec3b shade(const Eigen::Vector3d& n, const Eigen::Vector3d& albedo_bgr, bool mark_inside) {
  if (mark_inside && n.z() < 0) return {40, 30, 110};
  static const Eigen::Vector3d key = Eigen::Vector3d(-0.4, 0.6, 0.7).normalized();
  static const Eigen::Vector3d fill = Eigen::Vector3d(0.7, -0.1, 0.7).normalized();
  const double light = 0.18 + 0.65 * std::max(0.0, n.dot(key)) + 0.25 * std::max(0.0, n.dot(fill));
  const Eigen::Vector3d c = (255.0 * std::min(light, 1.0) * albedo_bgr).cwiseMin(255.0);
  return {static_cast<unsigned char>(c.x()), static_cast<unsigned char>(c.y()), static_cast<unsigned char>(c.z())};
}

}  // namespace

std::string shaded_preview_png(const TriangleMesh& boundary, const TriangleMesh& smooth, const PreviewOptions& options) {
  if (boundary.face_count() == 0) throw InvalidInput("preview: the boundary has no triangles");
  const TriangleMesh& right = smooth.face_count() > 0 ? smooth : boundary;
  const int size = options.panel_px;
  cv::Mat image(2 * size, 2 * size, CV_8UC3, cv::Scalar(245, 242, 240));
  // An oblique view 25° above the horizon; the second row from the far side.
  const Eigen::Vector3d up = options.up.normalized();
  const Eigen::Vector3d side = up.unitOrthogonal();
  const Eigen::Vector3d ahead = up.cross(side);
  const Eigen::Vector3d front = (0.9 * side + 0.45 * ahead + 0.45 * up).normalized();
  const Eigen::Vector3d back = (-0.9 * side - 0.45 * ahead + 0.45 * up).normalized();
  const Eigen::Vector3d clay(0.55, 0.72, 0.86), steel(0.86, 0.76, 0.62);  // BGR
  int row = 0;
  for (const Eigen::Vector3d& forward : {front, back}) {
    const OrthographicView view = fitted_view(boundary.vertices.positions, forward, size, size, up);
    int column = 0;
    for (const TriangleMesh* mesh : {&boundary, &right}) {
      const bool smooth_shading = column == 1;
      const Eigen::Vector3d albedo = smooth_shading ? steel : clay;
      const int x0 = column * size, y0 = row * size;
      rasterize(*mesh, smooth_shading, view, [&](int x, int y, const Eigen::Vector3d& n) {
        image.at<cv::Vec3b>(y0 + y, x0 + x) = shade(n, albedo, !smooth_shading);
      });
      ++column;
    }
    ++row;
  }
  std::vector<unsigned char> png;
  if (!image::encode(".png", image, png)) throw IoError("could not encode the preview as PNG");
  return std::string(png.begin(), png.end());
}

}  // namespace scanstation
