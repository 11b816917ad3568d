#include "acquisition/view_fusion.h"

#include "acquisition/outlier_removal.h"
#include "core/errors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace scanstation::acquisition {

namespace {

struct Cube {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d colour = Eigen::Vector3d::Zero();
  double weight = 0, doubt = 1;  // Σ cᵢ and Π(1 − cᵢ)
  int views = 0;
  std::size_t last_view = 0;
};

// 21 bits per axis, exact: no two cubes share a key.
std::uint64_t cube_key(const Eigen::Vector3d& p, double voxel) {
  constexpr std::int64_t half = std::int64_t{1} << 20;
  std::uint64_t key = 0;
  for (int k = 0; k < 3; ++k) {
    const double cell = std::floor(p[k] / voxel);
    if (!(cell >= -half && cell < half))
      throw InvalidInput("view fusion: a point lies more than 2^20 cubes of " + std::to_string(voxel) +
                         " from the origin (or is not finite)");
    key = (key << 21) | static_cast<std::uint64_t>(static_cast<std::int64_t>(cell) + half);
  }
  return key;
}

}  // namespace

LaserScanPoints fuse_views(const std::vector<LaserScanPoints>& views, const FusionOptions& options) {
  if (!(options.voxel > 0)) throw InvalidInput("view fusion: the voxel size must be positive");
  std::unordered_map<std::uint64_t, std::size_t> index;
  std::vector<Cube> cubes;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const LaserScanPoints& view = views[v];
    const Eigen::Index n = view.cloud.size();
    if ((view.cloud.has_colors() && view.cloud.colors.rows() != n) ||
        (!view.confidence.empty() && view.confidence.size() != static_cast<std::size_t>(n)))
      throw InvalidInput("view fusion: view " + std::to_string(v) + " has " + std::to_string(n) +
                         " points but a different number of colours or confidences");
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3d p = view.cloud.positions.row(i);
      const auto [it, added] = index.try_emplace(cube_key(p, options.voxel), cubes.size());
      if (added) cubes.emplace_back();
      Cube& cube = cubes[it->second];
      const double c = view.confidence.empty() ? 1.0 : view.confidence[static_cast<std::size_t>(i)];
      cube.position += c * p;
      if (view.cloud.has_colors()) cube.colour += c * view.cloud.colors.row(i).transpose().cast<double>();
      cube.weight += c;
      cube.doubt *= 1.0 - c;
      if (cube.views == 0 || cube.last_view != v) ++cube.views;
      cube.last_view = v;
    }
  }

  LaserScanPoints fused;
  std::vector<const Cube*> kept;
  for (const Cube& cube : cubes)
    if (cube.views >= options.minimum_views && cube.weight > 0) kept.push_back(&cube);
  const auto m = static_cast<Eigen::Index>(kept.size());
  fused.cloud.positions.resize(m, 3);
  fused.cloud.colors.resize(m, 3);
  for (Eigen::Index i = 0; i < m; ++i) {
    const Cube& cube = *kept[static_cast<std::size_t>(i)];
    fused.cloud.positions.row(i) = cube.position / cube.weight;
    for (int k = 0; k < 3; ++k)
      fused.cloud.colors(i, k) = static_cast<std::uint8_t>(std::lround(std::clamp(cube.colour[k] / cube.weight, 0.0, 255.0)));
    fused.confidence.push_back(1.0 - cube.doubt);
  }
  if (options.outlier_radius > 0) remove_isolated_points(fused, options.outlier_radius, options.min_neighbours);
  return fused;
}

}  // namespace scanstation::acquisition
