#include "smoothing/jet_fitted_vertices.h"

#include "core/errors.h"
#include "smoothing/same_side_neighbours.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace scanstation {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

constexpr int kLeastNeighbours = 10;
// cos 45°: as for the fitted normals, a jet turned further from the
// vertex's own faces does not stand for them.
constexpr double kMostFromFaces = 0.70710678118654752;
// Residuals above this many times the median are not noise. Chosen on the
// station's scans of the sphere, ellipsoid, torus, chalice and candlestick:
// at 1.5 too few noisy vertices move, and without a bound the candlestick's
// and chalice's rims are rounded off (docs/design.md, "Fitted positions").
constexpr double kMostResidual = 2.5;

Eigen::Vector3d vec(const Kernel::Vector_3& v) { return {v.x(), v.y(), v.z()}; }

struct Jet {
  Eigen::Vector3d origin, normal;
  double residual = -1.0;  // < 0: none fitted
};

// The jet of degree 2 through `near` (the vertex first), in its Monge form
// of degree 2 at the vertex's projection: origin, normal, principal
// directions and curvatures. The residual is each point's height over the
// Monge quadric ½(k1·x² + k2·y²), root mean square.
Jet fit_jet(const Eigen::MatrixX3d& V, const std::vector<Eigen::Index>& near) {
  std::vector<Kernel::Point_3> points;
  points.reserve(near.size());
  for (const Eigen::Index j : near) points.emplace_back(V(j, 0), V(j, 1), V(j, 2));
  CGAL::Monge_via_jet_fitting<Kernel> fitting;
  const auto form = fitting(points.begin(), points.end(), 2, 2);
  Jet jet;
  jet.origin = Eigen::Vector3d(form.origin().x(), form.origin().y(), form.origin().z());
  jet.normal = vec(form.normal_direction());
  const Eigen::Vector3d d1 = vec(form.maximal_principal_direction()), d2 = vec(form.minimal_principal_direction());
  const double k1 = form.coefficients()[0], k2 = form.coefficients()[1];
  double squares = 0.0;
  for (const Eigen::Index j : near) {
    const Eigen::Vector3d p = V.row(j).transpose() - jet.origin;
    const double x = p.dot(d1), y = p.dot(d2);
    const double height = p.dot(jet.normal) - 0.5 * (k1 * x * x + k2 * y * y);
    squares += height * height;
  }
  jet.residual = std::sqrt(squares / static_cast<double>(near.size()));
  if (!jet.origin.allFinite() || !jet.normal.allFinite() || !std::isfinite(jet.residual)) jet.residual = -1.0;
  return jet;
}

}  // namespace

JetFittedVertices jet_fitted_vertices(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int neighbours) {
  if (neighbours < kLeastNeighbours || neighbours > V.rows())
    throw InvalidInput("fitted positions: the neighbour count must be between " + std::to_string(kLeastNeighbours) +
                       " and the " + std::to_string(V.rows()) + " vertices, got " + std::to_string(neighbours));
  const SameSideNeighbours around(V, F);
  JetFittedVertices out;
  out.positions = V;
  std::vector<Jet> jets(static_cast<std::size_t>(V.rows()));
  std::vector<Eigen::Index> near;
  std::vector<double> residuals;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    around.near(v, neighbours, near);
    if (static_cast<int>(near.size()) < kLeastNeighbours) continue;
    Jet& jet = jets[static_cast<std::size_t>(v)];
    jet = fit_jet(V, near);
    if (jet.residual < 0.0) continue;
    const Eigen::Vector3d faces = around.side().row(v).normalized().transpose();
    if (jet.normal.dot(faces) < 0.0) jet.normal = -jet.normal;  // CGAL's Monge normal has no side
    if (jet.normal.dot(faces) < kMostFromFaces) {
      jet.residual = -1.0;
      continue;
    }
    residuals.push_back(jet.residual);
  }
  if (residuals.empty()) return out;
  std::nth_element(residuals.begin(), residuals.begin() + static_cast<std::ptrdiff_t>(residuals.size() / 2),
                   residuals.end());
  out.noise = residuals[residuals.size() / 2];
  std::vector<char> moved(static_cast<std::size_t>(V.rows()), 0);
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const Jet& jet = jets[static_cast<std::size_t>(v)];
    if (jet.residual < 0.0 || jet.residual > kMostResidual * out.noise) continue;
    out.positions.row(v) = jet.origin.transpose();
    moved[static_cast<std::size_t>(v)] = 1;
  }
  // A face the moves turn over (a sliver whose corner crossed its opposite
  // edge) gets its corners back where they were scanned, and so does every
  // face around a vertex whose faces no longer fit in one hemisphere (their
  // area-weighted normal's) when they did as scanned: there the sign
  // condition of §9.6 could fail where it held (stereo scans: a third fewer
  // folds). Until neither is left.
  const auto normal = [](const Eigen::MatrixX3d& P, const Eigen::MatrixX3i& faces, Eigen::Index f) {
    const Eigen::RowVector3d a = P.row(faces(f, 0)), b = P.row(faces(f, 1)), c = P.row(faces(f, 2));
    return Eigen::RowVector3d((b - a).cross(c - a));
  };
  std::vector<std::vector<Eigen::Index>> fan(static_cast<std::size_t>(V.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) fan[static_cast<std::size_t>(F(f, k))].push_back(f);
  const auto hemispherical = [&](const Eigen::MatrixX3d& P, Eigen::Index v) {
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (const Eigen::Index f : fan[static_cast<std::size_t>(v)]) sum += normal(P, F, f);
    for (const Eigen::Index f : fan[static_cast<std::size_t>(v)])
      if (normal(P, F, f).dot(sum) <= 0.0) return false;
    return true;
  };
  const auto revert = [&](Eigen::Index f) {
    bool any = false;
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(F(f, k));
      if (!moved[v]) continue;
      moved[v] = 0;
      out.positions.row(F(f, k)) = V.row(F(f, k));
      any = true;
    }
    return any;
  };
  std::vector<char> scanned_fits(static_cast<std::size_t>(V.rows()));
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    scanned_fits[static_cast<std::size_t>(v)] = !fan[static_cast<std::size_t>(v)].empty() && hemispherical(V, v);
  Eigen::MatrixX3d scanned_normals(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) scanned_normals.row(f) = normal(V, F, f);
  for (bool reverted = true; reverted;) {
    reverted = false;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      if (normal(out.positions, F, f).dot(scanned_normals.row(f)) <= 0.0) reverted = revert(f) || reverted;
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      if (scanned_fits[static_cast<std::size_t>(v)] && !hemispherical(out.positions, v))
        for (const Eigen::Index f : fan[static_cast<std::size_t>(v)]) reverted = revert(f) || reverted;
  }
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (moved[static_cast<std::size_t>(v)]) out.moved.push_back(static_cast<int>(v));
  return out;
}

}  // namespace scanstation
