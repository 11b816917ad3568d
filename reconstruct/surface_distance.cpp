#include "reconstruct/surface_distance.h"

#include "core/errors.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <cmath>
#include <vector>

namespace scanstation {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

struct SurfaceDistance::Tree {
  std::vector<Triangle> triangles;
  AabbTree tree;
};

SurfaceDistance::SurfaceDistance(const TriangleMesh& surface) : tree_(std::make_unique<Tree>()) {
  if (surface.face_count() == 0) throw InvalidInput("distance to a surface: the surface has no triangles");
  const auto& V = surface.vertices.positions;
  tree_->triangles.reserve(static_cast<std::size_t>(surface.face_count()));
  for (Eigen::Index f = 0; f < surface.face_count(); ++f) {
    const Triangle t(point(V.row(surface.faces(f, 0))), point(V.row(surface.faces(f, 1))),
                     point(V.row(surface.faces(f, 2))));
    if (!t.is_degenerate()) tree_->triangles.push_back(t);  // a degenerate triangle's edges belong to its neighbours
  }
  if (tree_->triangles.empty())
    throw InvalidInput("distance to a surface: every triangle of the surface is degenerate");
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;

Eigen::VectorXd SurfaceDistance::operator()(const Eigen::MatrixX3d& points) const {
  Eigen::VectorXd d(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i);
    if (!p.allFinite()) throw InvalidInput("distance to a surface: point " + std::to_string(i) + " is not finite");
    d(i) = std::sqrt(tree_->tree.squared_distance(point(p)));
  }
  return d;
}

Eigen::VectorXd distances_to_surface(const Eigen::MatrixX3d& points, const TriangleMesh& surface) {
  return SurfaceDistance(surface)(points);
}

Eigen::MatrixX3d surface_samples(const TriangleMesh& mesh, Eigen::Index max_samples) {
  const auto& V = mesh.vertices.positions;
  const Eigen::Index n = V.rows() + mesh.face_count();
  const Eigen::Index stride = max_samples > 0 && n > max_samples ? (n + max_samples - 1) / max_samples : 1;
  Eigen::MatrixX3d samples((n + stride - 1) / stride, 3);
  for (Eigen::Index i = 0, k = 0; i < n; i += stride, ++k) {
    if (i < V.rows()) {
      samples.row(k) = V.row(i);
    } else {
      const Eigen::Index f = i - V.rows();
      samples.row(k) = (V.row(mesh.faces(f, 0)) + V.row(mesh.faces(f, 1)) + V.row(mesh.faces(f, 2))) / 3.0;
    }
  }
  return samples;
}

DistanceSummary summarize_distances(const Eigen::VectorXd& d) {
  DistanceSummary s;
  s.count = d.size();
  if (d.size() == 0) return s;
  s.rms = std::sqrt(d.squaredNorm() / double(d.size()));
  s.mean = d.mean();
  s.max = d.maxCoeff();
  return s;
}

SurfaceDeviation surface_deviation(const TriangleMesh& mesh, const SurfaceDistance& to_truth,
                                   const Eigen::MatrixX3d& truth_samples, Eigen::Index max_samples) {
  SurfaceDeviation deviation;
  deviation.to_truth = summarize_distances(to_truth(surface_samples(mesh, max_samples)));
  deviation.from_truth = summarize_distances(SurfaceDistance(mesh)(truth_samples));
  return deviation;
}

SurfaceDeviation surface_deviation(const TriangleMesh& mesh, const TriangleMesh& truth, Eigen::Index max_samples) {
  return surface_deviation(mesh, SurfaceDistance(truth), surface_samples(truth, max_samples), max_samples);
}

nlohmann::json to_json(const DistanceSummary& s, double diagonal) {
  nlohmann::json j = {{"rms", s.rms}, {"mean", s.mean}, {"max", s.max}, {"samples", s.count}};
  if (diagonal > 0) j["rms_of_diagonal"] = s.rms / diagonal;
  return j;
}

}  // namespace scanstation
