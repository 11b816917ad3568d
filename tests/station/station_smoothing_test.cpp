// The station's smoothing settings on a boundary a turntable scan gave: the
// fitted vertex normals (smoothing/fitted_normals.h) keep the G¹ surface
// closer to the scanned object than the face normals of §9.4, and the
// fitted positions (smoothing/jet_fitted_vertices.h) take the scan's noise
// off it.
#include "core/io/mesh_io.h"
#include "reconstruct/surface_distance.h"
#include "sim/scan_objects.h"
#include "smoothing/surface_smoothing.h"
#include "smoothing/tessellation.h"
#include "station/session_processing.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace scanstation {
namespace {

TEST(StationSmoothing, FittedNormalsKeepTheSurfaceOfAScanCloserToTheObject) {
  // The demo's boundary of the built-in ellipsoid (tests/smoothing/data).
  const TriangleMesh boundary =
      io::read_mesh(std::filesystem::path(SCANSTATION_SOURCE_DIR) / "tests/smoothing/data/scanned_ellipsoid.ply");
  const TriangleMesh object = sim::scan_object("ellipsoid").on_platter;
  // mm: the boundary's vertices are scanned points of that object.
  ASSERT_LT(distances_to_surface(boundary.vertices.positions, object).maxCoeff(), 0.5);

  const SurfaceSmoothingOptions fitted = station::station_smoothing();
  ASSERT_GT(fitted.fitted_neighbours, 0);
  SurfaceSmoothingOptions faces = fitted;
  faces.fitted_neighbours = 0;  // the thesis' area-weighted normals
  const auto deviation = [&](const SurfaceSmoothingOptions& options) {
    return surface_deviation(tessellate(smooth_surface(boundary, options).surface, 2), object);
  };
  const SurfaceDeviation with_fitted = deviation(fitted), with_faces = deviation(faces);
  // Measured: rms 0.13 → 0.043 mm, Hausdorff 2.8 → 1.3 mm.
  EXPECT_LT(with_fitted.to_truth.rms, 0.5 * with_faces.to_truth.rms);
  EXPECT_LT(with_fitted.from_truth.rms, 0.5 * with_faces.from_truth.rms);
  EXPECT_LT(with_fitted.hausdorff(), with_faces.hausdorff());
}

// The station also moves the boundary's vertices onto jets fitted to their
// neighbours (smoothing/jet_fitted_vertices.h) before smoothing: the scan's
// noise then shapes the surface less, and fewer macro edges need the
// approximate join. (The boundary mesh itself still goes through every
// scanned point.)
TEST(StationSmoothing, FittedPositionsTakeTheScanNoiseOffTheSurface) {
  const TriangleMesh boundary =
      io::read_mesh(std::filesystem::path(SCANSTATION_SOURCE_DIR) / "tests/smoothing/data/scanned_ellipsoid.ply");
  const TriangleMesh object = sim::scan_object("ellipsoid").on_platter;
  const SurfaceSmoothingOptions fitted = station::station_smoothing();
  ASSERT_GT(fitted.jet_neighbours, 0);
  SurfaceSmoothingOptions scanned = fitted;
  scanned.jet_neighbours = 0;
  const SurfaceSmoothing with_fit = smooth_surface(boundary, fitted), without = smooth_surface(boundary, scanned);
  EXPECT_GT(with_fit.moved_vertices.size(), boundary.vertex_count() / 2);
  EXPECT_LT(with_fit.largest_move, 0.2);  // mm, on points with 0.02 mm of noise
  // The normals against the true ellipsoid's (radii 32, 20, 26 about (0, 0,
  // 26)) where the scan saw it, above the platter: measured 0.108 against
  // 0.119 rad RMS; the distance to it 0.033 against 0.034 mm RMS, the
  // approximate joins 73 against 87.
  const auto normal_error = [](const SurfaceSmoothing& s) {
    const TriangleMesh dense = tessellate(s.surface, 4);
    double squares = 0.0;
    int samples = 0;
    for (Eigen::Index v = 0; v < dense.vertex_count(); ++v) {
      const Eigen::RowVector3d p = dense.vertices.positions.row(v);
      if (p.z() < 10.0) continue;
      const Eigen::RowVector3d truth = Eigen::RowVector3d(p.x() / 1024, p.y() / 400, (p.z() - 26) / 676).normalized();
      squares += std::pow(std::acos(std::clamp(dense.vertices.normals.row(v).normalized().dot(truth), -1.0, 1.0)), 2);
      ++samples;
    }
    return std::sqrt(squares / samples);
  };
  EXPECT_LT(normal_error(with_fit), 0.95 * normal_error(without));
  EXPECT_LT(surface_deviation(tessellate(with_fit.surface, 2), object).to_truth.rms,
            surface_deviation(tessellate(without.surface, 2), object).to_truth.rms);
  EXPECT_LT(with_fit.surface.dependent_edges.size(), without.surface.dependent_edges.size());
}

}  // namespace
}  // namespace scanstation
