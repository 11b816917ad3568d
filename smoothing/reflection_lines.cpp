#include "smoothing/reflection_lines.h"

#include "core/errors.h"
#include "core/image_codecs.h"
#include "smoothing/orthographic_raster.h"

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace scanstation {

namespace {

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

}  // namespace

std::string reflection_lines_png(const TriangleMesh& smooth, const TriangleMesh& flat,
                                 const ReflectionLineOptions& options) {
  if (smooth.face_count() == 0 || flat.face_count() == 0)
    throw InvalidInput("reflection lines need triangle meshes with faces");
  const OrthographicView view = fitted_view(flat.vertices.positions, Eigen::Vector3d(0.45, 0.35, 0.82),
                                            options.width_px, options.height_px);
  cv::Mat image(options.height_px, 2 * options.width_px, CV_8UC1, cv::Scalar(90));
  const auto painter = [&](int x0) {
    return [&image, x0, &options](int x, int y, const Eigen::Vector3d& n) {
      image.at<unsigned char>(y, x0 + x) = reflection_shade(n, options.stripes);
    };
  };
  rasterize(smooth, true, view, painter(0));
  rasterize(flat, false, view, painter(options.width_px));
  std::vector<unsigned char> png;
  if (!image::encode(".png", image, png)) throw IoError("could not encode the reflection-line image as PNG");
  return std::string(png.begin(), png.end());
}

}  // namespace scanstation
