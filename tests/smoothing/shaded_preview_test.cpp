// The station's preview picture: every panel shows the object, and a wrongly
// oriented boundary shows its inside in red.
#include "core/errors.h"
#include "core/image_codecs.h"
#include "sim/shapes.h"
#include "smoothing/shaded_preview.h"
#include "smoothing/surface_smoothing.h"
#include "smoothing/tessellation.h"

#include <gtest/gtest.h>

namespace scanstation {
namespace {

cv::Mat decode(const std::string& png) {
  return image::decode(cv::Mat(1, static_cast<int>(png.size()), CV_8UC1, const_cast<char*>(png.data())),
                      cv::IMREAD_COLOR);
}

// Pixels of panel (row, column) that are not the background, and of those the dark-red ones.
std::pair<int, int> panel_pixels(const cv::Mat& image, int row, int column, int size) {
  int object = 0, red = 0;
  for (int y = row * size; y < (row + 1) * size; ++y)
    for (int x = column * size; x < (column + 1) * size; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      if (p == cv::Vec3b(245, 242, 240)) continue;
      ++object;
      red += p[2] > 100 && p[0] < 50;
    }
  return {object, red};
}

TEST(ShadedPreview, ShowsTheBoundaryAndTheSmoothSurfaceFromBothSides) {
  const TriangleMesh mesh = sim::ellipsoid({30, 20, 40}, 2);
  const TriangleMesh smooth = tessellate(smooth_surface(mesh).surface, 3);
  const cv::Mat image = decode(shaded_preview_png(mesh, smooth, {100, Eigen::Vector3d::UnitZ()}));
  ASSERT_EQ(image.rows, 200);
  ASSERT_EQ(image.cols, 200);
  for (int row = 0; row < 2; ++row)
    for (int column = 0; column < 2; ++column) {
      const auto [object, red] = panel_pixels(image, row, column, 100);
      EXPECT_GT(object, 100 * 100 / 4) << row << ", " << column;  // the object fills the panel
      EXPECT_EQ(red, 0) << "an outward-oriented surface shows no inside";
    }
}

// The picture of an object scaled by a power of two is the picture of the
// object: the boundary's face normals came out zero (black faces) for
// coordinates near 1e-160 and NaN near 1e160.
TEST(ShadedPreview, TheSamePictureAtAnyScale) {
  const TriangleMesh mesh = sim::ellipsoid({30, 20, 40}, 2);
  const TriangleMesh smooth = tessellate(smooth_surface(mesh).surface, 2);
  const std::string picture = shaded_preview_png(mesh, smooth, {64, Eigen::Vector3d::UnitZ()});
  for (const double scale : {0x1p-560, 0x1p560}) {
    TriangleMesh small_or_large = mesh, smooth_scaled = smooth;
    small_or_large.vertices.positions *= scale;
    smooth_scaled.vertices.positions *= scale;
    EXPECT_EQ(shaded_preview_png(small_or_large, smooth_scaled, {64, Eigen::Vector3d::UnitZ()}), picture) << scale;
  }
}

TEST(ShadedPreview, AnInsideOutBoundaryShowsRed) {
  TriangleMesh mesh = sim::icosphere(2);
  mesh.faces.col(1).swap(mesh.faces.col(2));
  const cv::Mat image = decode(shaded_preview_png(mesh, TriangleMesh{}, {80, Eigen::Vector3d::UnitZ()}));
  EXPECT_GT(panel_pixels(image, 0, 0, 80).second, 80 * 80 / 4);
  EXPECT_THROW(shaded_preview_png(TriangleMesh{}, TriangleMesh{}), InvalidInput);
}

}  // namespace
}  // namespace scanstation
