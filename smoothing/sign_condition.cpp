#include "smoothing/sign_condition.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

namespace scanstation {

namespace {

Eigen::MatrixX3d unit_face_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::MatrixX3d normals(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    normals.row(f) = n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
  }
  return normals;
}

// Smallest n · n_f over the faces of each vertex.
Eigen::VectorXd smallest_cosines(const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& face_normals,
                                 const Eigen::MatrixX3d& N) {
  Eigen::VectorXd smallest = Eigen::VectorXd::Constant(N.rows(), std::numeric_limits<double>::infinity());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int corner = 0; corner < 3; ++corner) {
      const int v = F(f, corner);
      smallest[v] = std::min(smallest[v], N.row(v).dot(face_normals.row(f)));
    }
  return smallest;
}

}  // namespace

std::vector<int> enforce_sign_condition(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, Eigen::MatrixX3d& N,
                                        double min_cosine) {
  const Eigen::MatrixX3d face_normals = unit_face_normals(V, F);
  const Eigen::VectorXd smallest = smallest_cosines(F, face_normals, N);
  std::vector<int> adjusted;
  for (int v = 0; v < N.rows(); ++v)
    if (smallest[v] < min_cosine) adjusted.push_back(v);
  if (adjusted.empty()) return adjusted;
  std::vector<std::vector<int>> faces_of(N.rows());
  for (int f = 0; f < F.rows(); ++f)
    for (int corner = 0; corner < 3; ++corner)
      if (smallest[F(f, corner)] < min_cosine) faces_of[F(f, corner)].push_back(f);
  // Maximise min_f n·n_f by subgradient ascent with a shrinking step (the
  // minimum over the faces is concave on the sphere's useful part); keep the
  // best direction seen.
  constexpr int max_steps = 2000;
  for (const int v : adjusted) {
    Eigen::Vector3d n = N.row(v), best = n;
    double best_cosine = -2.0;
    for (int step = 0; step < max_steps; ++step) {
      int worst = faces_of[v].front();
      for (const int f : faces_of[v])
        if (n.dot(face_normals.row(f)) < n.dot(face_normals.row(worst))) worst = f;
      const double cosine = n.dot(face_normals.row(worst));
      if (cosine > best_cosine) {
        best_cosine = cosine;
        best = n;
      }
      if (cosine >= min_cosine) break;
      n = (n + 0.5 / (1.0 + step / 20.0) * Eigen::Vector3d(face_normals.row(worst))).normalized();
    }
    N.row(v) = best.transpose();
  }
  return adjusted;
}

std::vector<int> sign_condition_violations(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                           const Eigen::MatrixX3d& N) {
  const Eigen::VectorXd smallest = smallest_cosines(F, unit_face_normals(V, F), N);
  std::vector<int> violations;
  for (int v = 0; v < N.rows(); ++v)
    if (smallest[v] <= 0.0) violations.push_back(v);
  return violations;
}

}  // namespace scanstation
