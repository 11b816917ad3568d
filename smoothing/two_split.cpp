#include "smoothing/two_split.h"

#include "smoothing/macro_patches.h"
#include "smoothing/tangent_plane_condition.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

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

// The ratio condition of Equations (9.7a) and (9.7e) around one pair, the
// part "an algorithm given by [Farin, 83]" does in the thesis. The macro
// patches are those of Steps 1–3; the cycle of outer edges is A → C → B → D
// → A (vertex i to vertex i+1, as the neighbours run them), `neighbour[i]`
// the macro patch across edge i with that edge as its local edge c[i],
// pair_macro P and Q (edges 0, 1 in P), and inner[i] the pair's point next to
// vertex i on its inner edge (K_A, W_C, K_B, W_D, first as subdivided), in
// the tangent plane of normal[i]. Per outer edge, E, F, G = (1, f, g)
// constant, fitted to the subdivided points at both ends; then the two
// Step-2 points of each outer edge and the four inner points move least (in
// their vertices' tangent planes) so that both ends meet (9.7a, e) exactly:
// with R0 = (V0 + K0 + O0)/3, the three-split's subdivided point,
//   (1 + g/3)(K0 − V0) + f(L0 − V0) + (g/3)(O0 − V0) = 0 at the start and
//   −(1 + f + 2g/3)(K3 − V3) + f(L2 − V3) + (g/3)(O3 − V3) = 0 at the end,
// sixteen linear equations in twenty-four tangent coordinates. Updates the
// macro patches (edge points, then Step 3 again), `inner` and `fg`; returns
// false when the system is dependent.
bool meet_ratio_conditions(const std::array<CubicTriangle*, 4>& neighbour, const std::array<int, 4>& c,
                           const std::array<CubicTriangle*, 2>& pair_macro, std::array<Vector3, 4>& inner,
                           const std::array<Vector3, 4>& normal, std::array<Eigen::Vector2d, 4>& fg) {
  struct End {
    Vector3 V, K, O;
    int K_index, O_index;
  };
  std::array<End, 8> ends;  // 2i: edge i at vertex i, 2i+1: at vertex i+1
  for (int i = 0; i < 4; ++i) {
    const CubicTriangle& N = *neighbour[i];
    const int a = c[i], b = (c[i] + 1) % 3, o = (c[i] + 2) % 3;
    ends[2 * i] = {N[corner(a)], N[next_to(a, b)], N[next_to(a, o)], next_to(a, b), next_to(a, o)};
    ends[2 * i + 1] = {N[corner(b)], N[next_to(b, a)], N[next_to(b, o)], next_to(b, a), next_to(b, o)};
  }
  // Fit (f, g) per edge to the subdivided points at both ends.
  for (int i = 0; i < 4; ++i) {
    const End& s = ends[2 * i];
    const End& t = ends[2 * i + 1];
    const Vector3 R0 = (s.V + s.K + s.O) / 3.0, R2 = (t.V + t.K + t.O) / 3.0;
    Eigen::Matrix<double, 6, 2> X;
    Eigen::Matrix<double, 6, 1> y;
    X << inner[i] - s.V, R0 - s.V, inner[(i + 1) % 4] - t.K, R2 - t.K;
    y << -(s.K - s.V), -(t.V - t.K);
    fg[i] = (X.transpose() * X).ldlt().solve(X.transpose() * y);
    // At a small angle of the thin triangle the subdivided L0 lies almost on
    // the edge line and the fit may give f or g of the wrong sign or near 0
    // (R1 would then be thrown far); the points are free to move instead.
    fg[i] = fg[i].cwiseMin(-0.2);
    if (!fg[i].allFinite()) return false;
  }
  Eigen::Matrix<double, 16, 24> J = Eigen::Matrix<double, 16, 24>::Zero();
  Eigen::Matrix<double, 16, 1> r;
  std::array<Eigen::Matrix<double, 3, 2>, 4> T;
  for (int v = 0; v < 4; ++v) T[v] = tangent_basis(normal[v]);
  for (int i = 0; i < 4; ++i)
    for (int end = 0; end < 2; ++end) {
      const End& e = ends[2 * i + end];
      const int v = (i + end) % 4;
      const double f = fg[i].x(), g = fg[i].y();
      const double k = end == 0 ? 1.0 + g / 3.0 : -(1.0 + f + 2.0 * g / 3.0);
      const int row = 2 * (2 * i + end);
      J.block<2, 2>(row, 2 * (2 * i + end)) = k * Eigen::Matrix2d::Identity();
      J.block<2, 2>(row, 16 + 2 * v) = f * Eigen::Matrix2d::Identity();
      r.segment<2>(row) = -T[v].transpose() * (k * (e.K - e.V) + f * (inner[v] - e.V) + g / 3.0 * (e.O - e.V));
    }
  const Eigen::LLT<Eigen::Matrix<double, 16, 16>> llt(J * J.transpose());
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Matrix<double, 24, 1> delta = J.transpose() * llt.solve(r);
  for (int i = 0; i < 4; ++i)
    for (int end = 0; end < 2; ++end) {
      const End& e = ends[2 * i + end];
      const int v = (i + end) % 4;
      const Vector3 K = e.K + T[v] * delta.segment<2>(2 * (2 * i + end));
      (*neighbour[i])[e.K_index] = K;
      // The same edge point in the pair's macro patch: the point next to
      // vertex v towards the other end of edge i.
      CubicTriangle& P = *pair_macro[i / 2];
      const Vector3& other_end = ends[2 * i + 1 - end].V;
      int at = -1, towards = -1;
      for (int k = 0; k < 3; ++k) {
        if (P[corner(k)] == e.V) at = k;
        if (P[corner(k)] == other_end) towards = k;
      }
      P[next_to(at, towards)] = K;
    }
  for (int v = 0; v < 4; ++v) inner[v] += T[v] * delta.segment<2>(16 + 2 * v);
  for (CubicTriangle* n : neighbour) set_centre_point(*n);
  for (CubicTriangle* f : pair_macro) set_centre_point(*f);
  return true;
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
        at_V(end_coefficients(K_ - V_, L0_ - V_, R0_ - V_)), at_Z(at_Z_) {}

  // The G¹ orientation (§9.6): L and R on opposite sides at both ends.
  bool oriented() const { return at_V.x() < 0.0 && at_V.y() < 0.0 && at_Z[0] > 0.0 && at_Z[1] < 0.0 && at_Z[2] < 0.0; }

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

  // Solves and writes the nine points; false when dependent.
  bool solve(CubicTriangle& P1, CubicTriangle& P2, CubicTriangle& Q1, CubicTriangle& Q2) const {
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
  // open: may be paired; three: an outer neighbour of a pair; blocked: next to
  // such a neighbour (the ratio conditions of one pair move the Step-2 points
  // of its outer edges, on which a neighbour's subdivided points depend, so no
  // three-split triangle may border two pairs).
  enum State : std::uint8_t { open, paired, three, blocked };
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
    // Its four outer neighbours: distinct, and not next to another pair.
    const std::array<int, 4> outer{edges.neighbour(f, (longest + 1) % 3), edges.neighbour(f, (longest + 2) % 3),
                                   edges.neighbour(g, (d + 1) % 3), edges.neighbour(g, (d + 2) % 3)};
    const auto unfit = [&](int n) {
      if (n == f || n == g || state[n] == paired) return true;
      for (int k = 0; k < 3; ++k) {
        const int m = edges.neighbour(n, k);
        if (m != f && m != g && state[m] == paired) return true;
      }
      return false;
    };
    if (std::any_of(outer.begin(), outer.end(), unfit)) continue;
    state[f] = state[g] = paired;
    for (const int n : outer) state[n] = three;
    for (const int n : outer)
      for (int k = 0; k < 3; ++k)
        if (state[edges.neighbour(n, k)] == open) state[edges.neighbour(n, k)] = blocked;
    pairs.push_back({f, longest});
  }
  return pairs;
}

BezierSurface two_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                        const MeshEdges& edges, const std::vector<TwoSplitPair>& pairs,
                        const ThreeSplitOptions& options) {
  std::vector<CubicTriangle> macro = macro_patches(V, F, N, options.tension);
  // Per pair, before any subdivision (it moves Step-2 points of the outer
  // edges): the ratio conditions, on copies of the six macro patches. The
  // cycle of vertices A, C, B, D and the outer edges A → C, C → B, B → D,
  // D → A as the neighbours run them. A pair whose result would violate the
  // G¹ orientation at an end of an inner edge is left to the three-split.
  struct PairData {
    int f, e, g, d;
    std::array<int, 4> neighbour, c;
    std::array<Vector3, 4> inner;
    std::array<Eigen::Vector2d, 4> fg;
  };
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
  std::vector<PairData> data;
  data.reserve(pairs.size());
  for (const TwoSplitPair& pair : pairs) {
    PairData p;
    p.f = pair.face;
    p.e = pair.edge;
    p.g = edges.neighbour(p.f, p.e);
    p.d = edges.neighbour_edge(p.f, p.e);
    const int local_edge[4][2] = {{p.f, (p.e + 2) % 3}, {p.f, (p.e + 1) % 3}, {p.g, (p.d + 2) % 3}, {p.g, (p.d + 1) % 3}};
    std::array<CubicTriangle, 6> m;
    for (int i = 0; i < 4; ++i) {
      p.neighbour[i] = edges.neighbour(local_edge[i][0], local_edge[i][1]);
      p.c[i] = edges.neighbour_edge(local_edge[i][0], local_edge[i][1]);
      m[i] = macro[p.neighbour[i]];
    }
    m[4] = macro[p.f];
    m[5] = macro[p.g];
    const int A = p.e, B = (p.e + 1) % 3, C = (p.e + 2) % 3, D = (p.d + 2) % 3;
    // As subdivided at Z: P[A, A, Z] = (A + K_AB)/2, P[C, C, Z] = (K_CA + K_CB)/2.
    p.inner = {(m[4][corner(A)] + m[4][next_to(A, B)]) / 2.0, (m[4][next_to(C, A)] + m[4][next_to(C, B)]) / 2.0,
               (m[4][corner(B)] + m[4][next_to(B, A)]) / 2.0,
               (m[5][next_to(D, p.d)] + m[5][next_to(D, (p.d + 1) % 3)]) / 2.0};
    const std::array<Vector3, 4> normal{N.row(F(p.f, A)), N.row(F(p.f, C)), N.row(F(p.f, B)), N.row(F(p.g, D))};
    if (!meet_ratio_conditions({&m[0], &m[1], &m[2], &m[3]}, p.c, {&m[4], &m[5]}, p.inner, normal, p.fg)) continue;
    std::array<CubicTriangle, 4> micro;
    split_pair(m[4], m[5], p, {&micro[0], &micro[1], &micro[2], &micro[3]});
    if (!PairStar(micro[0], micro[1], micro[2], micro[3]).oriented()) continue;
    for (int i = 0; i < 4; ++i) macro[p.neighbour[i]] = m[i];
    macro[p.f] = m[4];
    macro[p.g] = m[5];
    data.push_back(p);
  }
  std::vector<bool> in_pair(F.rows(), false);
  for (const PairData& p : data) in_pair[p.f] = in_pair[p.g] = true;
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
  for (const PairData& p : data) {
    const std::array<CubicTriangle*, 4> micro{&P[first[p.f]], &P[first[p.f] + 1], &P[first[p.g]], &P[first[p.g] + 1]};
    split_pair(macro[p.f], macro[p.g], p, micro);
    if (!PairStar(*micro[0], *micro[1], *micro[2], *micro[3]).solve(*micro[0], *micro[1], *micro[2], *micro[3]))
      ++surface.dependent_edges;
    for (int i = 0; i < 4; ++i) join_outer_edge({&P[first[p.neighbour[i]] + p.c[i]], p.fg[i]}, (*micro[i])[centre]);
  }
  for (int f = 0; f < F.rows(); ++f) {
    if (in_pair[f]) continue;
    for (int e = 0; e < 3; ++e) {
      const int g = edges.neighbour(f, e);
      if (f < g && !in_pair[g] &&
          !join_three_split_edge(P[first[f] + e], P[first[g] + edges.neighbour_edge(f, e)], options.least_squares_ratio))
        ++surface.dependent_edges;
    }
  }
  for (int f = 0; f < F.rows(); ++f)
    if (!in_pair[f]) join_three_split_interior(&P[first[f]]);
  return surface;
}

}  // namespace scanstation
