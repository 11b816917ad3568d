// Points hashed into cubes of a fixed side: every point within that distance
// of a query sits in one of the 27 cubes around it.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace scanstation::acquisition {

class PointGrid {
 public:
  /// points  #P by 3, referenced (must outlive the grid); cell  the search radius, > 0
  PointGrid(const Eigen::MatrixX3d& points, double cell) : points_(points), cell_(cell) {
    for (Eigen::Index i = 0; i < points.rows(); ++i) cells_[key(cell_of(points.row(i)))].push_back(i);
  }

  /// Indices of the points within `cell` of p.
  std::vector<Eigen::Index> within(const Eigen::Vector3d& p) const {
    std::vector<Eigen::Index> found;
    visit_within(p, [&](Eigen::Index i) {
      found.push_back(i);
      return false;
    });
    return found;
  }
  /// Whether a point lies within `cell` of p.
  bool any_within(const Eigen::Vector3d& p) const {
    return visit_within(p, [](Eigen::Index) { return true; });
  }

 private:
  // Calls visit(i) for the points within `cell` of p until it returns true;
  // returns whether it did.
  template <typename Visit>
  bool visit_within(const Eigen::Vector3d& p, Visit&& visit) const {
    const Eigen::Vector3i c = cell_of(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const Eigen::Index i : it->second)
            if ((points_.row(i).transpose() - p).squaredNorm() <= cell_ * cell_ && visit(i)) return true;
        }
    return false;
  }

  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const { return (p / cell_).array().floor().cast<int>(); }
  static std::uint64_t key(const Eigen::Vector3i& c) {
    const auto u = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)); };
    return u(c.x()) * 73856093u ^ u(c.y()) * 19349663u ^ u(c.z()) * 83492791u;
  }

  const Eigen::MatrixX3d& points_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<Eigen::Index>> cells_;
};

}  // namespace scanstation::acquisition
