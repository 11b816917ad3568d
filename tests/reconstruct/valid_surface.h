// The invariants every 3D boundary result must satisfy, shared by the
// constriction and Voronoi skeleton suites.
#pragma once

#include "core/mesh_measures.h"
#include "core/mesh_topology.h"
#include "core/self_intersections.h"
#include "reconstruct/boundary_reconstruction.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <string>

namespace scanstation {

// What every result must satisfy, whether or not all points were reached:
// a closed, oriented 2-manifold of genus 0 whose enclosed volume is that of
// the kept tetrahedra.
inline void expect_valid_surface(const SurfaceReconstruction& r, const std::string& what) {
  const MeshTopology t = mesh_topology(r.mesh);
  EXPECT_TRUE(t.closed) << what;
  EXPECT_TRUE(t.manifold) << what;
  EXPECT_TRUE(t.oriented) << what;
  EXPECT_EQ(t.genus, 0) << what;
  EXPECT_EQ(t.components, 1u) << what;
  const double volume = enclosed_volume(r.mesh.vertices.positions, r.mesh.faces);
  EXPECT_GT(volume, 0.0) << what;
  // The kept tetrahedra fill exactly the enclosed solid (§5.8).
  double kept = 0.0;
  for (Eigen::Index t = 0; t < r.interior.rows(); ++t) {
    const auto p = [&](int k) { return Eigen::Vector3d(r.mesh.vertices.positions.row(r.interior(t, k))); };
    kept += (p(1) - p(0)).cross(p(2) - p(0)).dot(p(3) - p(0)) / 6.0;
  }
  if (r.interior.rows() > 0) {
    EXPECT_NEAR(volume, kept, 1e-9 * std::abs(volume)) << what;
  }
  EXPECT_EQ(t.isolated_vertices, r.statistics.interior_vertices.size()) << what;
  EXPECT_EQ(self_intersections(r.mesh), std::optional<std::size_t>(0)) << what << ": not simple";
}

}  // namespace scanstation
