// G¹ orientation (thesis §9.6, §9.8): the tangent plane at a vertex must keep
// the incident triangles on their own side, or the patches meet in a ridge.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace scanstation {

/// The sign condition of §9.6 at a macro edge end M0 asks that L0 and R0, the
/// cross-edge control points of the two patches, lie on opposite sides of the
/// edge in the tangent plane (the thesis writes it as "f and g of opposite
/// sign"; with the signs of our Equation (9.3a), e0 = 1, it reads f0·g0 > 0).
/// With the projections of Step 2 this holds at every edge of vertex v
/// exactly when n_v · n_f > 0 for every incident face f (unit face normal
/// n_f). Vertices with min_f n_v · n_f < min_cosine get the normal that
/// raises that minimum most (subgradient ascent towards the worst face), up to
/// min_cosine; where the faces' normals fit in no open hemisphere no normal
/// helps and the vertex stays a violation (the mesh itself must change).
///
/// V #V by 3, F #F by 3, N #V by 3 unit normals (updated in place).
/// returns  the vertices whose normal was changed, ascending.
std::vector<int> enforce_sign_condition(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, Eigen::MatrixX3d& N,
                                        double min_cosine = 0.05);

/// The vertices violating the condition (min_f n_v·n_f ≤ 0), for reports and tests.
std::vector<int> sign_condition_violations(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                           const Eigen::MatrixX3d& N);

}  // namespace scanstation
