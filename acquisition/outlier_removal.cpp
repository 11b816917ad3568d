#include "acquisition/outlier_removal.h"

#include "acquisition/point_grid.h"
#include "core/errors.h"

namespace scanstation::acquisition {

Eigen::Index keep_points(LaserScanPoints& points, const std::vector<Eigen::Index>& kept) {
  PointCloud& cloud = points.cloud;
  const Eigen::Index removed = cloud.size() - static_cast<Eigen::Index>(kept.size());
  if (removed == 0) return 0;
  cloud.positions = cloud.positions(kept, Eigen::all).eval();
  if (cloud.has_colors()) cloud.colors = cloud.colors(kept, Eigen::all).eval();
  if (cloud.has_normals()) cloud.normals = cloud.normals(kept, Eigen::all).eval();
  if (!points.confidence.empty()) {
    std::vector<double> confidence;
    for (const Eigen::Index i : kept) confidence.push_back(points.confidence[static_cast<std::size_t>(i)]);
    points.confidence = std::move(confidence);
  }
  return removed;
}

Eigen::Index remove_isolated_points(LaserScanPoints& points, double radius, int min_neighbours,
                                    std::vector<Eigen::Index>* kept_out) {
  if (!(radius > 0)) throw InvalidInput("outlier removal: the radius must be positive");
  PointCloud& cloud = points.cloud;
  std::vector<Eigen::Index> kept;
  {
    const PointGrid grid(cloud.positions, radius);
    for (Eigen::Index i = 0; i < cloud.size(); ++i)
      if (static_cast<int>(grid.within(cloud.positions.row(i)).size()) - 1 >= min_neighbours) kept.push_back(i);
  }
  if (kept_out) *kept_out = kept;
  return keep_points(points, kept);
}

}  // namespace scanstation::acquisition
