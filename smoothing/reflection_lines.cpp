#include "smoothing/reflection_lines.h"

#include "core/errors.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <vector>

namespace scanstation {

namespace {

// Orthographic camera: looking along −forward, right and up span the image.
struct Camera {
  Eigen::Matrix3d rows;  // right, up, forward (towards the eye)
  Eigen::Vector3d centre;
  double pixels_per_unit;
  int width, height;

  Eigen::Vector3d to_screen(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d c = rows * (p - centre);
    return {width / 2.0 + c.x() * pixels_per_unit, height / 2.0 - c.y() * pixels_per_unit, c.z()};
  }
};

Camera camera_for(const Eigen::MatrixX3d& positions, int width, int height) {
  const Eigen::Vector3d forward = Eigen::Vector3d(0.45, 0.35, 0.82).normalized();
  const Eigen::Vector3d right = Eigen::Vector3d::UnitY().cross(forward).normalized();
  const Eigen::Vector3d up = forward.cross(right);
  Camera camera;
  camera.rows << right.transpose(), up.transpose(), forward.transpose();
  camera.centre = (positions.colwise().minCoeff() + positions.colwise().maxCoeff()).transpose() / 2.0;
  double extent = 0.0;
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    const Eigen::Vector3d c = camera.rows * (Eigen::Vector3d(positions.row(i)) - camera.centre);
    extent = std::max({extent, std::abs(c.x()), std::abs(c.y())});
  }
  camera.pixels_per_unit = 0.45 * std::min(width, height) / std::max(extent, std::numeric_limits<double>::min());
  camera.width = width;
  camera.height = height;
  return camera;
}

// Stripe colour of a unit normal in camera coordinates: reflect the view
// direction and cut the reflected directions into bands around the x axis.
unsigned char reflection_shade(const Eigen::Vector3d& n, double stripes) {
  const Eigen::Vector3d view(0.0, 0.0, 1.0);
  const double facing = n.dot(view);
  if (facing <= 0.0) return 40;
  const Eigen::Vector3d reflected = 2.0 * facing * n - view;
  const double angle = std::atan2(reflected.y(), reflected.z());
  const bool light = std::sin(stripes * angle) > 0.0;
  return static_cast<unsigned char>((light ? 255.0 : 20.0) * (0.35 + 0.65 * facing));
}

// Z-buffered rasterisation of one mesh into the image columns [x0, x0+width).
void render(const TriangleMesh& mesh, bool flat, const Camera& camera, int x0, double stripes, cv::Mat& image) {
  std::vector<double> depth(static_cast<std::size_t>(camera.width) * camera.height,
                            -std::numeric_limits<double>::infinity());
  const bool smooth_normals = !flat && mesh.vertices.has_normals();
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    Eigen::Vector3d p[3], n[3];
    for (int c = 0; c < 3; ++c) p[c] = camera.to_screen(mesh.vertices.positions.row(mesh.faces(f, c)));
    const Eigen::Vector3d face = camera.rows * (Eigen::Vector3d(mesh.vertices.positions.row(mesh.faces(f, 1))) -
                                                 Eigen::Vector3d(mesh.vertices.positions.row(mesh.faces(f, 0))))
                                                    .cross(Eigen::Vector3d(mesh.vertices.positions.row(mesh.faces(f, 2))) -
                                                           Eigen::Vector3d(mesh.vertices.positions.row(mesh.faces(f, 0))));
    for (int c = 0; c < 3; ++c)
      n[c] = smooth_normals ? Eigen::Vector3d(camera.rows * mesh.vertices.normals.row(mesh.faces(f, c)).transpose())
                            : face.normalized();
    const double area = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[2].x() - p[0].x()) * (p[1].y() - p[0].y());
    if (area == 0.0) continue;
    const int xmin = std::max(0, int(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int xmax = std::min(camera.width - 1, int(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int ymin = std::max(0, int(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int ymax = std::min(camera.height - 1, int(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = ymin; y <= ymax; ++y)
      for (int x = xmin; x <= xmax; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        const double w0 = ((p[1].x() - px) * (p[2].y() - py) - (p[2].x() - px) * (p[1].y() - py)) / area;
        const double w1 = ((p[2].x() - px) * (p[0].y() - py) - (p[0].x() - px) * (p[2].y() - py)) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double z = w0 * p[0].z() + w1 * p[1].z() + w2 * p[2].z();
        double& stored = depth[static_cast<std::size_t>(y) * camera.width + x];
        if (z <= stored) continue;
        stored = z;
        const Eigen::Vector3d normal = (w0 * n[0] + w1 * n[1] + w2 * n[2]).normalized();
        image.at<unsigned char>(y, x0 + x) = reflection_shade(normal, stripes);
      }
  }
}

}  // namespace

std::string reflection_lines_png(const TriangleMesh& smooth, const TriangleMesh& flat,
                                 const ReflectionLineOptions& options) {
  if (smooth.face_count() == 0 || flat.face_count() == 0)
    throw InvalidInput("reflection lines need triangle meshes with faces");
  const Camera camera = camera_for(flat.vertices.positions, options.width_px, options.height_px);
  cv::Mat image(options.height_px, 2 * options.width_px, CV_8UC1, cv::Scalar(90));
  render(smooth, false, camera, 0, options.stripes, image);
  render(flat, true, camera, options.width_px, options.stripes, image);
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) throw IoError("could not encode the reflection-line image as PNG");
  return std::string(png.begin(), png.end());
}

}  // namespace scanstation
