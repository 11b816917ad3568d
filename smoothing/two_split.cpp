#include "smoothing/two_split.h"

#include "smoothing/damped_least_squares.h"
#include "smoothing/macro_patches.h"
#include "smoothing/tangent_plane_condition.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <unordered_map>
#include <utility>
#include <vector>

namespace scanstation {

namespace {

using Vector3 = Eigen::Vector3d;

// Index of the control point next to corner a on the patch edge towards b.
int next_to(int a, int b) {
  int exponent[3] = {0, 0, 0};
  exponent[a] = 2;
  exponent[b] = 1;
  return control_index(exponent[0], exponent[1], exponent[2]);
}

// Index of corner a.
int corner(int a) {
  int exponent[3] = {0, 0, 0};
  exponent[a] = 3;
  return control_index(exponent[0], exponent[1], exponent[2]);
}

constexpr int centre = control_index(1, 1, 1);

double smallest_angle(const Vector3& a, const Vector3& b, const Vector3& c) {
  const auto angle = [](const Vector3& u, const Vector3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); };
  return std::min({angle(b - a, c - a), angle(c - b, a - b), angle(a - c, b - c)});
}

// An outer edge of a pair, between a two-split micro triangle and the
// three-split neighbour `other` (three-split micro triangle k of a face lies
// on its edge k, b300 → b030): M0..M3 on the edge in other's direction; f, g
// the constant coefficients of Equation (9.7).
struct OuterEdge {
  CubicTriangle* other;
  Eigen::Vector2d fg;
  const Vector3& M(int i) const { return (*other)[control_index(3 - i, i, 0)]; }
};

Eigen::Matrix<double, 3, 2> tangent_basis(const Vector3& n) {
  Eigen::Matrix<double, 3, 2> T;
  T.col(0) = n.unitOrthogonal();
  T.col(1) = n.cross(T.col(0)).normalized();
  return T;
}

// One candidate pair: P = face f split on its edge e (A → B), Q = face g
// (edge d, B → A); the cycle of vertices A, C, B, D and the outer edges A →
// C, C → B, B → D, D → A as the three-split neighbours run them: outer edge
// i is local edge c[i] of face neighbour[i], from vertex[i] to vertex[i+1];
// inner[i] the pair's point next to vertex i on its inner edge (K_A, W_C,
// K_B, W_D); fg[i] the constant coefficients of Equation (9.7) on edge i.
struct PairData {
  int f, e, g, d;
  std::array<int, 4> neighbour, c, vertex;
  std::array<Vector3, 4> inner;
  std::array<Eigen::Vector2d, 4> fg;
};

// The corner of `face` at vertex v.
int local_corner(const Eigen::MatrixX3i& F, int face, int v) {
  return F(face, 0) == v ? 0 : F(face, 1) == v ? 1 : 2;
}

// The Step-2 point of `face` next to vertex v towards vertex w.
Vector3& edge_point(std::vector<CubicTriangle>& macro, const Eigen::MatrixX3i& F, int face, int v, int w) {
  return macro[face][next_to(local_corner(F, face, v), local_corner(F, face, w))];
}

std::uint64_t directed(int v, int w) { return std::uint64_t(std::uint32_t(v)) << 32 | std::uint32_t(w); }

// Per outer edge, E, F, G = (1, f, g) constant (Equation 9.7), fitted to
// the subdivided points at both ends of the macro patches of Steps 1–3:
// (K0 − V0) + f(L0 − V0) + g(R0 − V0) = 0 and (V3 − K3) + f(L2 − K3) + g(R2 −
// K3) = 0 by least squares, R = (V + K + O)/3 the neighbour's subdivided
// point. False when not finite.
bool fit_outer_coefficients(PairData& p, const std::vector<CubicTriangle>& macro) {
  for (int i = 0; i < 4; ++i) {
    const CubicTriangle& N = macro[p.neighbour[i]];
    const int a = p.c[i], b = (p.c[i] + 1) % 3, o = (p.c[i] + 2) % 3;
    const Vector3 &Va = N[corner(a)], &Ka = N[next_to(a, b)], &Vb = N[corner(b)], &Kb = N[next_to(b, a)];
    const Vector3 R0 = (Va + Ka + N[next_to(a, o)]) / 3.0, R2 = (Vb + Kb + N[next_to(b, o)]) / 3.0;
    Eigen::Matrix<double, 6, 2> X;
    Eigen::Matrix<double, 6, 1> y;
    X << p.inner[i] - Va, R0 - Va, p.inner[(i + 1) % 4] - Kb, R2 - Kb;
    y << -(Ka - Va), -(Vb - Kb);
    p.fg[i] = (X.transpose() * X).ldlt().solve(X.transpose() * y);
    // At a small angle of the thin triangle the subdivided L0 lies almost on
    // the edge line and the fit may give f or g of the wrong sign or near 0
    // (R1 would then be thrown far); the points are free to move instead.
    p.fg[i] = p.fg[i].cwiseMin(-0.2);
    if (!p.fg[i].allFinite()) return false;
  }
  return true;
}

// The ratio condition of Equations (9.7a) and (9.7e) around the active
// pairs, the part "an algorithm given by [Farin, 83]" does in the thesis. With
// R0 = (V0 + K0 + O0)/3, the three-split neighbour's subdivided point (K0, O0
// its Step-2 points at V0 on the outer edge and on its other edge), E, F, G =
// (1, f, g) constant on each outer edge:
//   (1 + g/3)(K0 − V0) + f(L0 − V0) + (g/3)(O0 − V0) = 0 at the start and
//   −(1 + f + 2g/3)(K3 − V3) + f(L2 − V3) + (g/3)(O3 − V3) = 0 at the end,
// L the pair's inner point. The Step-2 points of every outer edge and the
// inner points move least, in their vertices' tangent planes, so that all
// ends meet it. A three-split triangle that borders two or three pairs (the
// thesis' "two or three sides of a triangle are split") couples them: the O
// of one pair's end is a K of the other's, so such pairs are solved together
// (one least-norm system per group of coupled pairs, sixteen equations per
// pair; a lone pair is the old 16 × 24 system). Moves the macro patches' edge
// points (then Step 3 again) and the pairs' inner points; returns the pairs
// (indices into `pairs`) of groups whose system was dependent, which are left
// unmoved.
std::vector<int> meet_ratio_conditions(std::vector<PairData>& pairs, const std::vector<int>& active,
                                       std::vector<CubicTriangle>& macro, const Eigen::MatrixX3i& F,
                                       const Eigen::MatrixX3d& N, const MeshEdges& edges) {
  // Unknowns: the two Step-2 points of each outer edge (keyed by their vertex
  // and the edge's other vertex, shared by the neighbour and the pair
  // triangle), then the four inner points of each pair.
  struct EdgePoint {
    int v, w, three, owner;  // owner: index into `active`
  };
  std::vector<EdgePoint> points;
  std::unordered_map<std::uint64_t, int> point_of;
  for (int a = 0; a < int(active.size()); ++a) {
    const PairData& p = pairs[active[a]];
    for (int i = 0; i < 4; ++i) {
      const int v = p.vertex[i], w = p.vertex[(i + 1) % 4];
      for (const auto& [from, to] : {std::pair{v, w}, std::pair{w, v}}) {
        point_of.emplace(directed(from, to), int(points.size()));
        points.push_back({from, to, p.neighbour[i], a});
      }
    }
  }
  // Groups of coupled pairs (union–find over the O points that are unknowns).
  std::vector<int> group(active.size());
  for (int a = 0; a < int(active.size()); ++a) group[a] = a;
  const auto root = [&group](int a) {
    while (group[a] != a) a = group[a] = group[group[a]];
    return a;
  };
  const auto other_point = [&](const PairData& p, int i, int end) {  // O at that end, or −1
    const int three = p.neighbour[i], o = F(three, (p.c[i] + 2) % 3);
    const auto it = point_of.find(directed(p.vertex[(i + end) % 4], o));
    return it == point_of.end() ? -1 : it->second;
  };
  for (int a = 0; a < int(active.size()); ++a)
    for (int i = 0; i < 4; ++i)
      for (int end = 0; end < 2; ++end)
        if (const int o = other_point(pairs[active[a]], i, end); o >= 0) group[root(a)] = root(points[o].owner);
  std::vector<std::vector<int>> members(active.size()), member_points(active.size());
  for (int a = 0; a < int(active.size()); ++a) members[root(a)].push_back(a);
  for (int k = 0; k < int(points.size()); ++k) member_points[root(points[k].owner)].push_back(k);

  std::vector<int> dependent;
  std::vector<int> column(points.size(), -1);
  std::vector<Eigen::Matrix<double, 3, 2>> basis(N.rows());
  std::vector<bool> has_basis(N.rows(), false);
  const auto tangent = [&](int v) -> const Eigen::Matrix<double, 3, 2>& {
    if (!has_basis[v]) basis[v] = tangent_basis(N.row(v)), has_basis[v] = true;
    return basis[v];
  };
  for (std::size_t root_of_group = 0; root_of_group < members.size(); ++root_of_group) {
    const std::vector<int>& member = members[root_of_group];
    const std::vector<int>& group_points = member_points[root_of_group];
    if (member.empty()) continue;
    // Columns: 2 per edge point of the group, then 2 per inner point.
    for (std::size_t j = 0; j < group_points.size(); ++j) column[group_points[j]] = 2 * int(j);
    const int inner_column = 2 * int(group_points.size());
    const int rows = 16 * int(member.size()), columns = inner_column + 8 * int(member.size());
    std::vector<Eigen::Triplet<double>> J;
    J.reserve(std::size_t(rows) * 3);
    Eigen::VectorXd r(rows);
    for (int m = 0; m < int(member.size()); ++m) {
      const PairData& p = pairs[active[member[m]]];
      for (int i = 0; i < 4; ++i)
        for (int end = 0; end < 2; ++end) {
          const int v = p.vertex[(i + end) % 4], w = p.vertex[(i + 1 - end) % 4];
          const int three = p.neighbour[i], o = F(three, (p.c[i] + 2) % 3);
          const double f = p.fg[i].x(), g = p.fg[i].y();
          const double k = end == 0 ? 1.0 + g / 3.0 : -(1.0 + f + 2.0 * g / 3.0);
          const Vector3& V = macro[three][corner(local_corner(F, three, v))];
          const Vector3& K = edge_point(macro, F, three, v, w);
          const Vector3& O = edge_point(macro, F, three, v, o);
          const int row = 16 * m + 4 * i + 2 * end;
          const int K_column = column[point_of.at(directed(v, w))], O_point = other_point(p, i, end);
          const int L_column = inner_column + 8 * m + 2 * ((i + end) % 4);
          for (int t = 0; t < 2; ++t) {
            J.emplace_back(row + t, K_column + t, k);
            J.emplace_back(row + t, L_column + t, f);
            if (O_point >= 0) J.emplace_back(row + t, column[O_point] + t, g / 3.0);
          }
          r.segment<2>(row) =
              -tangent(v).transpose() * (k * (K - V) + f * (p.inner[(i + end) % 4] - V) + g / 3.0 * (O - V));
        }
    }
    Eigen::SparseMatrix<double> A(rows, columns);
    A.setFromTriplets(J.begin(), J.end());
    const Eigen::SparseMatrix<double> normal = A * A.transpose();
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(normal);
    Eigen::VectorXd delta;
    bool solved = ldlt.info() == Eigen::Success;
    if (solved) {
      delta = A.transpose() * ldlt.solve(r);
      delta += A.transpose() * ldlt.solve(r - A * delta);  // refined once
      solved = delta.allFinite() && (A * delta - r).norm() <= 1e-9 * r.norm() + 1e-300;
    }
    if (!solved) {
      for (const int a : member) dependent.push_back(active[a]);
      continue;
    }
    // The moved points, written to both faces that hold each, and Step 3.
    std::vector<int> touched;
    for (std::size_t j = 0; j < group_points.size(); ++j) {
      const EdgePoint& e = points[group_points[j]];
      const Vector3 K = edge_point(macro, F, e.three, e.v, e.w) + tangent(e.v) * delta.segment<2>(2 * int(j));
      const int l = local_corner(F, e.three, e.v), across = edges.neighbour(e.three, F(e.three, (l + 1) % 3) == e.w ? l : (l + 2) % 3);
      for (const int face : {e.three, across}) {
        edge_point(macro, F, face, e.v, e.w) = K;
        touched.push_back(face);
      }
    }
    for (int m = 0; m < int(member.size()); ++m) {
      PairData& p = pairs[active[member[m]]];
      for (int v = 0; v < 4; ++v) p.inner[v] += tangent(p.vertex[v]) * delta.segment<2>(inner_column + 8 * m + 2 * v);
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (const int face : touched) set_centre_point(macro[face]);
  }
  return dependent;
}

// Step 5 of §9.7. Unknowns, one row each.
enum Unknown { Z, YA, YB, YC, YD, XP1, XP2, XQ1, XQ2, unknowns };
using System = Eigen::Matrix<double, unknowns, unknowns>;
using Points = Eigen::Matrix<double, unknowns, 3>;

// One inner edge V → Z with linear E, F, G (Equation 9.3): M = (V, K, Y, Z),
// rows L = (L0, X_L, Y_L), R = (R0, X_R, Y_R); (1, f0, g0) at V by (9.3a),
// at_Z = (e1, f1, g1) at Z.
struct LinearEdge {
  LinearEdge() = default;
  Vector3 V, K, L0, R0;
  Unknown Y, XL, YL, XR, YR;
  Eigen::Vector2d at_V;
  Vector3 at_Z;
  LinearEdge(const Vector3& V_, const Vector3& K_, Unknown Y_, const Vector3& L0_, Unknown XL_, Unknown YL_,
             const Vector3& R0_, Unknown XR_, Unknown YR_, const Vector3& at_Z_)
      : V(V_), K(K_), L0(L0_), R0(R0_), Y(Y_), XL(XL_), YL(YL_), XR(XR_), YR(YR_),
        at_V(end_coefficients(K_ - V_, L0_ - V_, R0_ - V_)), at_Z(at_Z_) {
    // at_Z's sign is free too: the one that gives F and G the signs they
    // have at V, so that neither passes through zero along the edge (where
    // the surface would fold, see HalfEdge in six_split.cpp).
    if (at_V.x() * at_Z[1] < 0.0 && at_V.y() * at_Z[2] < 0.0) at_Z = -at_Z;
  }

  // The G¹ orientation (§9.6): F/G > 0 all along the edge, i.e. f0, g0, f1
  // and g1 of one sign.
  bool oriented() const {
    return at_V.x() * at_V.y() > 0.0 && at_V.x() * at_Z[1] > 0.0 && at_V.y() * at_Z[2] > 0.0 &&
           end_fits(K - V, L0 - V, R0 - V, at_V);
  }

  void rows(System& A, Points& rhs, int row) const {
    const double f0 = at_V.x(), g0 = at_V.y(), e1 = at_Z[0], f1 = at_Z[1], g1 = at_Z[2];
    // (9.3b): e1(K − V) + 2(Y − K) + f1(L0 − V) + 2f0(X_L − K) + g1(R0 − V) + 2g0(X_R − K) = 0
    A(row, Y) += 2.0;
    A(row, XL) += 2.0 * f0;
    A(row, XR) += 2.0 * g0;
    rhs.row(row) = (-e1 * (K - V) + 2.0 * (1.0 + f0 + g0) * K - f1 * (L0 - V) - g1 * (R0 - V)).transpose();
    // (9.3c): 2e1(Y − K) + (Z − Y) + 2f1(X_L − K) + f0(Y_L − Y) + 2g1(X_R − K) + g0(Y_R − Y) = 0
    A(row + 1, Y) += 2.0 * e1 - 1.0 - f0 - g0;
    A(row + 1, Z) += 1.0;
    A(row + 1, XL) += 2.0 * f1;
    A(row + 1, YL) += f0;
    A(row + 1, XR) += 2.0 * g1;
    A(row + 1, YR) += g0;
    rhs.row(row + 1) = (2.0 * (e1 + f1 + g1) * K).transpose();
  }
};

// The coefficients (e1, f1, g1) at Z of the edge whose point next to Z is y_own,
// with sides y_left, y_right, read from a relation ρ among y = Y − Z
// (indices A, B, C, D = 0..3) that leaves out the fourth point:
// e1(Z − Y_own) + f1(Y_left − Y_own) + g1(Y_right − Y_own) = Σ ρ_i y_i.
Vector3 at_Z(const Eigen::Vector4d& rho, int own, int left, int right) {
  const Vector3 c(-(rho[own] + rho[left] + rho[right]), rho[left], rho[right]);
  // The scale is free (the ratio e1/e0 of §9.6): e1 = 1 like the three-split
  // where that is well defined.
  return std::abs(c[0]) > 0.25 * c.norm() ? Vector3(c / c[0]) : Vector3(c / c.norm());
}

// Step 5 of §9.7 for one pair, micro triangles P1 = (A, Z, C), P2 = (Z, B, C),
// Q1 = (B, Z, D), Q2 = (Z, A, D): the nine unknowns X_i, Y_i, Z of Figure 9.6
// under nine linear conditions.
class PairStar {
 public:
  PairStar(const CubicTriangle& P1, const CubicTriangle& P2, const CubicTriangle& Q1, const CubicTriangle& Q2) {
    const Vector3 A = P1[corner(0)], B = P2[corner(1)], C = P1[corner(2)], D = Q1[corner(2)];
    C_ = C;
    W_C_ = P1[next_to(2, 1)];
    reach_ = 100.0 * ((A - B).norm() + (C - D).norm());
    old_.row(Z) = P1[corner(1)].transpose();
    old_.row(YA) = P1[next_to(1, 0)].transpose();
    old_.row(YB) = P2[next_to(0, 1)].transpose();
    old_.row(YC) = P1[next_to(1, 2)].transpose();
    old_.row(YD) = Q1[next_to(1, 2)].transpose();
    old_.row(XP1) = P1[centre].transpose();
    old_.row(XP2) = P2[centre].transpose();
    old_.row(XQ1) = Q1[centre].transpose();
    old_.row(XQ2) = Q2[centre].transpose();
    const auto y_old = [&](Unknown u) { return Vector3(old_.row(u) - old_.row(Z)); };
    // C–Z: E, F, G constant (Equation 9.5a at C, L = P1, R = P2).
    fg_C_ = end_coefficients(W_C_ - C, P1[next_to(2, 0)] - C, P2[next_to(2, 1)] - C);
    const double fC = fg_C_.x(), gC = fg_C_.y(), sC = 1.0 + fC + gC;
    // The star at Z: (9.5c) on C–Z, and y_D = α y_A + β y_C fitted to the
    // subdivided points; every other inner edge's coefficients at Z follow.
    ab_ = end_coefficients(-y_old(YD), y_old(YA), y_old(YC));
    const double alpha = ab_.x(), beta = ab_.y();
    const Eigen::Vector4d R_C(fC, gC, -sC, 0.0), R_fit(-alpha, 0.0, -beta, 1.0);
    edges_ = {LinearEdge(A, P1[next_to(0, 1)], YA, P1[next_to(0, 2)], XP1, YC, Q2[next_to(1, 2)], XQ2, YD,
                         at_Z(R_fit, 0, 2, 3)),
              LinearEdge(B, P2[next_to(1, 0)], YB, Q1[next_to(0, 2)], XQ1, YD, P2[next_to(1, 2)], XP2, YC,
                         at_Z(alpha * R_C + fC * R_fit, 1, 3, 2)),
              LinearEdge(D, Q1[next_to(2, 1)], YD, Q1[next_to(2, 0)], XQ1, YB, Q2[next_to(2, 1)], XQ2, YA,
                         at_Z(beta * R_C - sC * R_fit, 3, 1, 0))};
  }

  // The G¹ orientation at both ends of all four inner edges.
  bool oriented() const {
    return fg_C_.x() < 0.0 && fg_C_.y() < 0.0 &&
           std::all_of(edges_.begin(), edges_.end(), [](const LinearEdge& e) { return e.oriented(); });
  }

  // Solves and writes the nine points; false when dependent, or when the
  // exact solution would move a point farther than max_move times the pair's
  // mean diagonal (a bulge: then the bounded damped step, not G¹ there).
  bool solve(CubicTriangle& P1, CubicTriangle& P2, CubicTriangle& Q1, CubicTriangle& Q2, double max_move) const {
    const double fC = fg_C_.x(), gC = fg_C_.y(), sC = 1.0 + fC + gC;
    System M = System::Zero();
    Points rhs = Points::Zero();
    // (9.6a) on C–Z: (Y_C − W_C) + f(X_P1 − W_C) + g(X_P2 − W_C) = 0.
    M(0, YC) = 1.0;
    M(0, XP1) = fC;
    M(0, XP2) = gC;
    rhs.row(0) = (sC * W_C_).transpose();
    // (9.6b) on C–Z: (Z − Y_C) + f(Y_A − Y_C) + g(Y_B − Y_C) = 0.
    M(1, Z) = 1.0;
    M(1, YC) = -sC;
    M(1, YA) = fC;
    M(1, YB) = gC;
    // The fitted relation y_D = α y_A + β y_C.
    M(2, YD) = 1.0;
    M(2, YA) = -ab_.x();
    M(2, YC) = -ab_.y();
    M(2, Z) = ab_.x() + ab_.y() - 1.0;
    for (int e = 0; e < 3; ++e) edges_[e].rows(M, rhs, 3 + 2 * e);
    // Solved as a correction of the subdivided points, refined once.
    const Eigen::FullPivLU<System> lu(M);
    Points x = old_;
    bool met = lu.rank() == unknowns;
    if (met) {
      for (int step = 0; step < 2; ++step) x += lu.solve(rhs - M * x);
      met = (x - old_).rowwise().norm().maxCoeff() <= reach_;
    }
    if (!met) {
      Eigen::CompleteOrthogonalDecomposition<System> cod;
      cod.setThreshold(1e-6);
      cod.compute(M);
      x = old_ + cod.solve(rhs - M * old_);
    }
    const double bound = max_move * reach_ / 200.0;  // reach_ is 100 × the sum of the diagonals
    if ((x - old_).rowwise().norm().maxCoeff() > bound) {
      x = old_ + damped_step(M, rhs - M * old_, bound);
      met = false;
    }
    const Vector3 z = x.row(Z);
    P1[corner(1)] = P2[corner(0)] = Q1[corner(1)] = Q2[corner(0)] = z;
    P1[next_to(1, 0)] = Q2[next_to(0, 1)] = x.row(YA).transpose();
    P2[next_to(0, 1)] = Q1[next_to(1, 0)] = x.row(YB).transpose();
    P1[next_to(1, 2)] = P2[next_to(0, 2)] = x.row(YC).transpose();
    Q1[next_to(1, 2)] = Q2[next_to(0, 2)] = x.row(YD).transpose();
    P1[centre] = x.row(XP1).transpose();
    P2[centre] = x.row(XP2).transpose();
    Q1[centre] = x.row(XQ1).transpose();
    Q2[centre] = x.row(XQ2).transpose();
    return met;
  }

 private:
  Vector3 C_, W_C_;
  double reach_;
  Points old_;
  Eigen::Vector2d fg_C_, ab_;
  std::array<LinearEdge, 3> edges_;
};

// (9.7b) − (9.7a): (M2 − M1) + f(L1 − M1) + g(R1 − M1) = 0 gives R1, with
// L1 the pair's micro triangle centre.
void join_outer_edge(const OuterEdge& e, const Vector3& L1) {
  const Vector3 M1 = e.M(1);
  (*e.other)[centre] = M1 - ((e.M(2) - M1) + e.fg.x() * (L1 - M1)) / e.fg.y();
}

}  // namespace

std::vector<TwoSplitPair> two_split_pairs(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                          const MeshEdges& edges, double min_angle_degrees) {
  const double min_angle = min_angle_degrees * M_PI / 180.0;
  std::vector<std::pair<double, int>> thin;
  for (int f = 0; f < F.rows(); ++f) {
    const double angle = smallest_angle(V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2)));
    if (angle < min_angle) thin.emplace_back(angle, f);
  }
  std::sort(thin.begin(), thin.end());
  // open: may be paired; three: an outer neighbour of a pair (three-split,
  // and it may border further pairs: their ratio conditions are solved
  // together).
  enum State : std::uint8_t { open, paired, three };
  std::vector<State> state(F.rows(), open);
  std::vector<TwoSplitPair> pairs;
  for (const auto& [angle, f] : thin) {
    if (state[f] != open) continue;
    int longest = 0;
    for (int e = 1; e < 3; ++e)
      if ((V.row(F(f, (e + 1) % 3)) - V.row(F(f, e))).squaredNorm() >
          (V.row(F(f, (longest + 1) % 3)) - V.row(F(f, longest))).squaredNorm())
        longest = e;
    const int g = edges.neighbour(f, longest), d = edges.neighbour_edge(f, longest);
    if (g == f || state[g] != open) continue;
    // Its four outer neighbours: three-split (not in a pair, nor the pair).
    const std::array<int, 4> outer{edges.neighbour(f, (longest + 1) % 3), edges.neighbour(f, (longest + 2) % 3),
                                   edges.neighbour(g, (d + 1) % 3), edges.neighbour(g, (d + 2) % 3)};
    if (std::any_of(outer.begin(), outer.end(), [&](int n) { return n == f || n == g || state[n] == paired; }))
      continue;
    state[f] = state[g] = paired;
    for (const int n : outer) state[n] = three;
    pairs.push_back({f, longest});
  }
  return pairs;
}

BezierSurface two_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                        const MeshEdges& edges, const std::vector<TwoSplitPair>& pairs,
                        const ThreeSplitOptions& options, TwoSplitCounts* counts) {
  const std::vector<CubicTriangle> subdivided = macro_patches(V, F, N, options.tension);
  const auto split_pair = [](const CubicTriangle& Pm, const CubicTriangle& Qm, const PairData& p,
                             const std::array<CubicTriangle*, 4>& micro) {
    // Step 4: P = (A, B, C) and Q = (B, A, D) split at Z = P(½, ½, 0) = Q(½, ½, 0).
    const Barycentric a = Barycentric::Unit(p.e), b = Barycentric::Unit((p.e + 1) % 3),
                      c = Barycentric::Unit((p.e + 2) % 3);
    const Barycentric qb = Barycentric::Unit(p.d), qa = Barycentric::Unit((p.d + 1) % 3),
                      qd = Barycentric::Unit((p.d + 2) % 3);
    *micro[0] = subpatch(Pm, a, (a + b) / 2.0, c);
    *micro[1] = subpatch(Pm, (a + b) / 2.0, b, c);
    *micro[2] = subpatch(Qm, qb, (qa + qb) / 2.0, qd);
    *micro[3] = subpatch(Qm, (qa + qb) / 2.0, qa, qd);
    (*micro[0])[next_to(0, 1)] = (*micro[3])[next_to(1, 0)] = p.inner[0];  // K_A
    (*micro[0])[next_to(2, 1)] = (*micro[1])[next_to(2, 0)] = p.inner[1];  // W_C
    (*micro[1])[next_to(1, 0)] = (*micro[2])[next_to(0, 1)] = p.inner[2];  // K_B
    (*micro[2])[next_to(2, 1)] = (*micro[3])[next_to(2, 0)] = p.inner[3];  // W_D
  };
  // The candidates with their subdivided inner points and fitted (f, g),
  // from the macro patches of Steps 1–3.
  std::vector<PairData> candidates;
  candidates.reserve(pairs.size());
  for (const TwoSplitPair& pair : pairs) {
    PairData p;
    p.f = pair.face;
    p.e = pair.edge;
    p.g = edges.neighbour(p.f, p.e);
    p.d = edges.neighbour_edge(p.f, p.e);
    const int local_edge[4][2] = {{p.f, (p.e + 2) % 3}, {p.f, (p.e + 1) % 3}, {p.g, (p.d + 2) % 3}, {p.g, (p.d + 1) % 3}};
    for (int i = 0; i < 4; ++i) {
      p.neighbour[i] = edges.neighbour(local_edge[i][0], local_edge[i][1]);
      p.c[i] = edges.neighbour_edge(local_edge[i][0], local_edge[i][1]);
    }
    const int A = p.e, B = (p.e + 1) % 3, C = (p.e + 2) % 3, D = (p.d + 2) % 3;
    p.vertex = {F(p.f, A), F(p.f, C), F(p.f, B), F(p.g, D)};
    const CubicTriangle &Pm = subdivided[p.f], &Qm = subdivided[p.g];
    // As subdivided at Z: P[A, A, Z] = (A + K_AB)/2, P[C, C, Z] = (K_CA + K_CB)/2.
    p.inner = {(Pm[corner(A)] + Pm[next_to(A, B)]) / 2.0, (Pm[next_to(C, A)] + Pm[next_to(C, B)]) / 2.0,
               (Pm[corner(B)] + Pm[next_to(B, A)]) / 2.0, (Qm[next_to(D, p.d)] + Qm[next_to(D, (p.d + 1) % 3)]) / 2.0};
    if (fit_outer_coefficients(p, subdivided)) candidates.push_back(p);
  }
  // The ratio conditions of all pairs together, then the G¹ orientation of
  // each pair's inner edges; a pair that fails it (or whose group's ratio
  // system is dependent) is left to the three-split, and the others are
  // solved again without it.
  std::vector<int> active(candidates.size());
  for (int k = 0; k < int(active.size()); ++k) active[k] = k;
  std::vector<CubicTriangle> macro;
  std::vector<PairData> data;
  for (;;) {
    macro = subdivided;
    data = candidates;
    std::vector<int> dropped = meet_ratio_conditions(data, active, macro, F, N, edges);
    for (const int k : active) {
      if (std::find(dropped.begin(), dropped.end(), k) != dropped.end()) continue;
      std::array<CubicTriangle, 4> micro;
      split_pair(macro[data[k].f], macro[data[k].g], data[k], {&micro[0], &micro[1], &micro[2], &micro[3]});
      if (!PairStar(micro[0], micro[1], micro[2], micro[3]).oriented()) dropped.push_back(k);
    }
    if (dropped.empty()) break;
    std::sort(dropped.begin(), dropped.end());
    std::vector<int> kept;
    std::set_difference(active.begin(), active.end(), dropped.begin(), dropped.end(), std::back_inserter(kept));
    active = std::move(kept);
  }
  std::vector<bool> in_pair(F.rows(), false);
  std::vector<int> borders(F.rows(), 0);  // pairs a three-split triangle borders
  for (const int k : active) {
    in_pair[data[k].f] = in_pair[data[k].g] = true;
    for (const int n : data[k].neighbour) ++borders[n];
  }
  if (counts) {
    counts->pairs = active.size();
    counts->adjacent_pairs = std::count_if(active.begin(), active.end(), [&](int k) {
      return std::any_of(data[k].neighbour.begin(), data[k].neighbour.end(), [&](int n) { return borders[n] > 1; });
    });
  }
  std::vector<int> first(F.rows() + 1, 0);
  for (int f = 0; f < F.rows(); ++f) first[f + 1] = first[f] + (in_pair[f] ? 2 : 3);
  BezierSurface surface;
  surface.patches.resize(first.back());
  surface.macro.resize(first.back());
  auto& P = surface.patches;
  for (int f = 0; f < F.rows(); ++f) {
    for (int j = first[f]; j < first[f + 1]; ++j) surface.macro[j] = f;
    if (!in_pair[f]) split_in_three(macro[f], &P[first[f]]);
  }
  for (const int k : active) {
    const PairData& p = data[k];
    const std::array<CubicTriangle*, 4> micro{&P[first[p.f]], &P[first[p.f] + 1], &P[first[p.g]], &P[first[p.g] + 1]};
    split_pair(macro[p.f], macro[p.g], p, micro);
    if (!PairStar(*micro[0], *micro[1], *micro[2], *micro[3])
             .solve(*micro[0], *micro[1], *micro[2], *micro[3], options.max_move))
      surface.dependent_edges.push_back({std::min(p.f, p.g), std::max(p.f, p.g)});
    for (int i = 0; i < 4; ++i) join_outer_edge({&P[first[p.neighbour[i]] + p.c[i]], p.fg[i]}, (*micro[i])[centre]);
  }
  for (int f = 0; f < F.rows(); ++f) {
    if (in_pair[f]) continue;
    for (int e = 0; e < 3; ++e) {
      const int g = edges.neighbour(f, e);
      if (f < g && !in_pair[g] &&
          !join_three_split_edge(P[first[f] + e], P[first[g] + edges.neighbour_edge(f, e)], options.least_squares_ratio,
                                 options.max_move))
        surface.dependent_edges.push_back({f, g});
    }
  }
  for (int f = 0; f < F.rows(); ++f)
    if (!in_pair[f]) join_three_split_interior(&P[first[f]]);
  return surface;
}

}  // namespace scanstation
