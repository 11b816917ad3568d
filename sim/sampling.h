// Seeded point samples of known surfaces and outlines, with optional
// Gaussian noise: the scattered input whose true boundary is known.
#pragma once

#include "core/point_cloud.h"
#include "core/polygon.h"
#include "core/triangle_mesh.h"

#include <cstdint>

namespace scanstation::sim {

/// `count` points uniformly distributed by area over the mesh's triangles,
/// each displaced along a normal direction by N(0, noise²); positions and
/// the true unit normals of the triangles they came from. The same seed
/// gives the same points on every machine. Throws InvalidInput for a mesh
/// without area or a negative noise.
PointCloud sample_surface(const TriangleMesh& mesh, Eigen::Index count, std::uint64_t seed, double noise = 0.0);

/// `count` points uniformly distributed by arc length along the closed
/// polygon, in boundary order, each moved by N(0, noise²) in x and y.
/// Returns #count by 2.
Eigen::MatrixX2d sample_outline(const Polygon2& outline, Eigen::Index count, std::uint64_t seed, double noise = 0.0);

/// The points moved by independent N(0, sigma²) offsets in every coordinate.
Eigen::MatrixXd add_gaussian_noise(const Eigen::MatrixXd& points, double sigma, std::uint64_t seed);

}  // namespace scanstation::sim
