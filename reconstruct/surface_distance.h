// Distance from points to a triangulated surface (CGAL AABB_tree), the
// measure of a scan or a reconstruction against a known true surface.
#pragma once

#include "core/triangle_mesh.h"

#include <Eigen/Core>
#include <memory>
#include <nlohmann/json.hpp>

namespace scanstation {

/// A triangulated surface ready for distance queries (its AABB tree built
/// once). The surface needs a non-degenerate triangle (throws InvalidInput).
class SurfaceDistance {
 public:
  explicit SurfaceDistance(const TriangleMesh& surface);
  ~SurfaceDistance();
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;

  /// Unsigned distance of every row of `points` (#P by 3) to the nearest
  /// point of the surface. Throws InvalidInput for a non-finite point.
  Eigen::VectorXd operator()(const Eigen::MatrixX3d& points) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

/// SurfaceDistance(surface)(points).
Eigen::VectorXd distances_to_surface(const Eigen::MatrixX3d& points, const TriangleMesh& surface);

/// Statistics of a set of distances (all zero for none).
struct DistanceSummary {
  double rms = 0, mean = 0, max = 0;
  Eigen::Index count = 0;
};
DistanceSummary summarize_distances(const Eigen::VectorXd& distances);

/// The vertices and face centroids of `mesh`, every k-th of them when there
/// are more than `max_samples` (0: all), in order.
Eigen::MatrixX3d surface_samples(const TriangleMesh& mesh, Eigen::Index max_samples = 0);

/// How far `mesh` lies from `truth` both ways: from the mesh's samples to
/// the truth, and from the truth's samples to the mesh (surface_samples, at
/// most `max_samples` each way). The larger maximum is the sampled Hausdorff
/// distance.
struct SurfaceDeviation {
  DistanceSummary to_truth, from_truth;
  double hausdorff() const { return std::max(to_truth.max, from_truth.max); }
};
SurfaceDeviation surface_deviation(const TriangleMesh& mesh, const TriangleMesh& truth, Eigen::Index max_samples = 0);
/// The same with the truth's distance structure and samples prepared once.
SurfaceDeviation surface_deviation(const TriangleMesh& mesh, const SurfaceDistance& to_truth,
                                   const Eigen::MatrixX3d& truth_samples, Eigen::Index max_samples = 0);

/// {"rms", "mean", "max", "samples"} and, when `diagonal` > 0, "rms_of_diagonal".
nlohmann::json to_json(const DistanceSummary& summary, double diagonal = 0.0);

}  // namespace scanstation
