// Meshes shared by the smoothing tests: generated shapes, randomly perturbed
// closed meshes and real meshes from Debian's libcgal-demo data.
#pragma once

#include "core/io/mesh_io.h"
#include "sim/random.h"
#include "smoothing/mesh_edges.h"
#include "smoothing/sign_condition.h"
#include "smoothing/six_split.h"
#include "smoothing/vertex_normals.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <filesystem>
#include <string>
#include <vector>

namespace scanstation::test {

/// An icosphere of 2 subdivisions with every vertex moved radially by up to ±amount.
inline TriangleMesh bumpy_sphere(std::uint64_t seed, double amount) {
  TriangleMesh mesh = sim::icosphere(2);
  sim::Random random(seed);
  for (Eigen::Index v = 0; v < mesh.vertex_count(); ++v)
    mesh.vertices.positions.row(v) *= 1.0 + amount * (2.0 * random.uniform() - 1.0);
  return mesh;
}

/// Closed, oriented meshes from libcgal-demo (genus 0, and knot1 of genus 1)
/// on which the sign condition holds and no macro edge is symmetric.
inline std::vector<std::string> real_mesh_names() { return {"bunny00.off", "elephant.off", "eight.off", "knot1.off"}; }

inline TriangleMesh real_mesh(const std::string& name) { return io::read_mesh(cgal_data("meshes/" + name)); }

/// The boundary a simulated 24-step turntable scan of an ellipsoid gave
/// (tests/smoothing/data): thin macro triangles near the axis, nearly
/// dependent macro edges, a cap with a 175° angle.
inline TriangleMesh scanned_boundary() {
  return io::read_mesh(std::filesystem::path(SCANSTATION_SOURCE_DIR) / "tests/smoothing/data/scanned_ellipsoid.ply");
}

/// What the split schemes take: area-weighted normals, turned where the sign
/// condition fails (§9.6), and the mesh's edges.
struct SchemeInput {
  Eigen::MatrixX3d N;
  MeshEdges edges;
};
inline SchemeInput scheme_input(const TriangleMesh& mesh) {
  SchemeInput in{vertex_normals(mesh.vertices.positions, mesh.faces), mesh_edges(mesh.faces)};
  enforce_sign_condition(mesh.vertices.positions, mesh.faces, in.N);
  return in;
}

/// The six-split surface (§9.8) of a mesh with its scheme_input.
inline BezierSurface six_split_surface(const TriangleMesh& mesh) {
  const SchemeInput in = scheme_input(mesh);
  return six_split(mesh.vertices.positions, mesh.faces, in.N, in.edges);
}

}  // namespace scanstation::test
