#include "smoothing/six_split.h"

#include "smoothing/damped_least_squares.h"
#include "smoothing/normals_apart.h"
#include "smoothing/macro_patches.h"
#include "smoothing/tangent_plane_condition.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#ifdef __linux__
#include <sys/mman.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace scanstation {

namespace {

using Point = Eigen::Vector3d;

// Step 5 moves the points around a macro edge's midpoint at most this many
// macro edge lengths, unless max_move is smaller; an exact solution that
// folds the surface, at most half an edge length (see join_macro_edge).
constexpr double kReach = 100.0, kFoldReach = 0.5;

// Control points of a micro triangle (A, B, O): A = b300, B = b030, O = b003.
constexpr int A_corner = control_index(3, 0, 0), B_corner = control_index(0, 3, 0), O_corner = control_index(0, 0, 3);
constexpr int outer_near_A = control_index(2, 1, 0), outer_near_B = control_index(1, 2, 0);
constexpr int AO_near_A = control_index(2, 0, 1), AO_near_O = control_index(1, 0, 2);
constexpr int BO_near_B = control_index(0, 2, 1), BO_near_O = control_index(0, 1, 2);
constexpr int centre = control_index(1, 1, 1);

// Step 0: N − V = τ((K0 − V) + (K1 − V)) at the macro vertices, τ = 2/3.
constexpr double vertex_edge_ratio = 2.0 / 3.0;

// Steps 1–4 for one macro triangle (corners V_c, edge midpoints Z_c, centroid
// O; edge c runs from V_c to V_n, n = c+1): the blossom values P[r_a, r_b,
// r_c] that Steps 5–7 read, by de Casteljau at the fixed parameters ½ (along
// the edges) and ⅓ (towards O), with the control point indices fixed at
// compile time.
//   K_c = P[V_c, V_c, Z_c], Kn_c = P[V_n, V_n, Z_c], Y_a = P[Z_c, Z_c, V_c],
//   Y_b = P[Z_c, Z_c, V_n], Z_c, Y_c = P[Z_c, Z_c, O], the centres X_a =
//   P[V_c, Z_c, O], X_b = P[Z_c, V_n, O], and N_c on the edge V_c → O by
//   Equation (9.14).
struct FaceSplit {
  Point V[3], K[3], Kn[3], N[3], Z[3], Ya[3], Yb[3], Y[3], Xa[3], Xb[3];
};

// What Step 5 reads from the other macro triangle of edge d: N at V_d and at
// V_d+1, Y_d, X_a, X_b.
struct FarSide {
  Point N_start, N_end, Y, Xa, Xb;
};

constexpr int quadratic_index(int i, int k) { return (2 - i) * (3 - i) / 2 + k; }  // as blossom_level

// Per edge c: the macro control points V_c, b(c → n), b(n → c), V_n, b(c →
// c−1), and the points of P[O, ·, ·] at 2u_c, u_c + u_n, 2u_n.
struct EdgeIndex {
  int corner, towards_n, towards_c, corner_n, towards_previous, q_cc, q_cn, q_nn;
};

constexpr std::array<EdgeIndex, 3> edge_index = [] {
  std::array<EdgeIndex, 3> index{};
  const auto cubic = [](int c, int ec, int m, int em) {
    int e[3] = {0, 0, 0};
    e[c] += ec;
    e[m] += em;
    return control_index(e[0], e[1], e[2]);
  };
  const auto quadratic = [](int c, int m) {
    int e[3] = {0, 0, 0};
    ++e[c];
    ++e[m];
    return quadratic_index(e[0], e[2]);
  };
  for (int c = 0; c < 3; ++c) {
    const int n = (c + 1) % 3, p = (c + 2) % 3;
    index[c] = {cubic(c, 3, n, 0), cubic(c, 2, n, 1), cubic(c, 1, n, 2), cubic(n, 3, c, 0),
                cubic(c, 2, p, 1), quadratic(c, c), quadratic(c, n), quadratic(n, n)};
  }
  return index;
}();

// P[O, ·, ·]: q_ijk = (b_(i+1)jk + b_i(j+1)k + b_ij(k+1))/3.
std::array<Point, 6> quadratic_at_centroid(const CubicTriangle& b) {
  std::array<Point, 6> q;
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; i + j <= 2; ++j) {
      const int k = 2 - i - j;
      q[quadratic_index(i, k)] =
          (b[control_index(i + 1, j, k)] + b[control_index(i, j + 1, k)] + b[control_index(i, j, k + 1)]) / 3.0;
    }
  return q;
}

// N_c − V_c = ⅔((K_c − V_c) + (Kn_c−1 − V_c)), K_c = (V_c + b(c → n))/2,
// Kn_c−1 = (V_c + b(c → c−1))/2.
Point step_four_point(const CubicTriangle& b, int c) {
  const Point& V = b[edge_index[c].corner];
  return V + vertex_edge_ratio * ((b[edge_index[c].towards_n] + V) / 2.0 - V +
                                  ((b[edge_index[c].towards_previous] + V) / 2.0 - V));
}

void split_face(const CubicTriangle& b, FaceSplit& s) {
  const std::array<Point, 6> q = quadratic_at_centroid(b);
  for (int c = 0; c < 3; ++c) {
    const EdgeIndex& at = edge_index[c];
    s.V[c] = b[at.corner];
    const Point& e0 = b[at.towards_n];
    const Point& e1 = b[at.towards_c];
    // The boundary cubic (V_c, e0, e1, V_n) at ½.
    s.K[c] = (s.V[c] + e0) / 2.0;
    const Point middle = (e0 + e1) / 2.0;
    s.Kn[c] = (e1 + b[at.corner_n]) / 2.0;
    s.Ya[c] = (s.K[c] + middle) / 2.0;
    s.Yb[c] = (middle + s.Kn[c]) / 2.0;
    s.Z[c] = (s.Ya[c] + s.Yb[c]) / 2.0;
    // P[O, Z_c, ·] at V_c and V_n; Y_c = P[O, Z_c, Z_c] is their mean.
    s.Xa[c] = (q[at.q_cc] + q[at.q_cn]) / 2.0;
    s.Xb[c] = (q[at.q_cn] + q[at.q_nn]) / 2.0;
    s.Y[c] = (s.Xa[c] + s.Xb[c]) / 2.0;
    s.N[c] = step_four_point(b, c);
  }
}

FarSide far_side(const CubicTriangle& b, int d) {
  const std::array<Point, 6> q = quadratic_at_centroid(b);
  const EdgeIndex& at = edge_index[d];
  FarSide t;
  t.N_start = step_four_point(b, d);
  t.N_end = step_four_point(b, (d + 1) % 3);
  t.Xa = (q[at.q_cc] + q[at.q_cn]) / 2.0;
  t.Xb = (q[at.q_cn] + q[at.q_nn]) / 2.0;
  t.Y = (t.Xa + t.Xb) / 2.0;
  return t;
}

// The nine points of Step 5 around a macro edge's midpoint Z, seen from one
// of its two macro triangles: Y_a, Y_b the edge points next to Z (towards
// V_c, V_n), Y = P[Z, Z, O] and the centres X_a, X_b of this side's micro
// triangles (V_c, Z, O), (Z, V_n, O).
struct EdgeSide {
  Point Z, Ya, Yb, Y, Xa, Xb;
};

// Equation (9.3b, c) on the half edge V → Z with M = (V, K, Y, Z), rows L =
// (N_here, X_here, Y_here), R = (N_there, X_there, Y_there); E, F, G linear
// from (1, f0, g0) at V (Equation 9.3a) to (e1, f1, g1) at Z:
//   (9.3b) e1(K − V) + 2(Y − K) + f1(N_here − V) + 2f0(X_here − K) + g1(N_there − V) + 2g0(X_there − K) = 0
//   (9.3c) 2e1(Y − K) + (Z − Y) + 2f1(X_here − K) + f0(Y_here − Y) + 2g1(X_there − K) + g0(Y_there − Y) = 0
// with the unknowns' coefficients (2, 2f0, 2g0) and (2e1 − 1 − f0 − g0 at
// Y, 1 at Z, 2f1, 2g1, f0, g0), and these right-hand sides.
//
// Where the condition holds, E·along + F·here + G·there = 0 all along the
// half edge, so along × there = −(F/G) along × here: the two patches' normals
// point the same way exactly where F/G > 0. (9.3a) and (9.3d) fix (e0, f0,
// g0) and (e1, f1, g1) each up to its own factor only; the thesis takes e0 =
// e1 = 1, but when the signs of (f0, g0) and of the star's (φ, ψ) differ
// (a thin macro triangle whose cross-edge points lean back from V, as at the
// cap of a turntable scan), F and G then both pass through zero between V
// and Z and the surface folds between them — a singular point on each side,
// often narrower than any sampling. e1 = −1 keeps F and G off zero instead
// (E passes through it, where here and there point exactly apart).
struct HalfEdge {
  double f0, g0, e1, f1, g1;
  double y_c;  // Y's coefficient in (9.3c)
  Point rhs_b, rhs_c;
  bool end_fits;  // (9.3a) holds at V (see end_fits)
};

HalfEdge half_edge(const Point& V, const Point& K, const Point& N_here, const Point& N_there,
                   const Eigen::Vector2d& at_Z) {
  const Eigen::Vector2d c0 = end_coefficients(K - V, N_here - V, N_there - V);
  const double e1 = (c0.x() * at_Z.x() < 0.0 && c0.y() * at_Z.y() < 0.0) ? -1.0 : 1.0;
  HalfEdge h{c0.x(), c0.y(), e1, e1 * at_Z.x(), e1 * at_Z.y(), 2.0 * e1 - 1.0 - c0.x() - c0.y(), {}, {},
             end_fits(K - V, N_here - V, N_there - V, c0)};
  h.rhs_b = -e1 * (K - V) + 2.0 * K - h.f1 * (N_here - V) - h.g1 * (N_there - V) + 2.0 * (h.f0 + h.g0) * K;
  h.rhs_c = 2.0 * (e1 + h.f1 + h.g1) * K;
  return h;
}

// Unknowns of Step 5 in the fallback, one row each.
enum Unknown { Z, Ya, Yb, Yf, Yg, Xa, Xb, Xa_there, Xb_there, unknowns };
using Constraints = Eigen::Matrix<double, 8, unknowns>;
using Points = Eigen::Matrix<double, unknowns, 3>;

// All eight constraints of Step 5 as A x = rhs on the nine points.
Constraints step5_constraints(double phi, double psi, const HalfEdge& a, const HalfEdge& b,
                              Eigen::Matrix<double, 8, 3>& rhs) {
  Constraints A = Constraints::Zero();
  rhs.setZero();
  const auto mean_row = [&A](int row, Unknown of, Unknown first, Unknown second) {
    A(row, of) = 1.0;
    A(row, first) = -0.5;
    A(row, second) = -0.5;
  };
  mean_row(0, Z, Ya, Yb);
  A(1, Z) = 1.0;  // (Z − Y_a) + φ(Y_f − Y_a) + ψ(Y_g − Y_a) = 0
  A(1, Ya) = -(1.0 + phi + psi);
  A(1, Yf) = phi;
  A(1, Yg) = psi;
  mean_row(2, Yf, Xa, Xb);
  mean_row(3, Yg, Xa_there, Xb_there);
  const auto half_edge_rows = [&](int row, const HalfEdge& h, Unknown Y, Unknown X_here, Unknown X_there) {
    A(row, Y) = 2.0;
    A(row, X_here) = 2.0 * h.f0;
    A(row, X_there) = 2.0 * h.g0;
    rhs.row(row) = h.rhs_b.transpose();
    A(row + 1, Y) = h.y_c;
    A(row + 1, Z) = 1.0;
    A(row + 1, X_here) = 2.0 * h.f1;
    A(row + 1, X_there) = 2.0 * h.g1;
    A(row + 1, Yf) = h.f0;
    A(row + 1, Yg) = h.g0;
    rhs.row(row + 1) = h.rhs_c.transpose();
  };
  half_edge_rows(4, a, Ya, Xa, Xa_there);
  half_edge_rows(6, b, Yb, Xb, Xb_there);
  return A;
}

// The closest point of the well-posed part of all eight constraints
// (pseudo-inverse, small singular values dropped), for (nearly) dependent
// constraints: true when it meets them all the same without moving a point
// farther than `reach`.
bool pseudo_inverse_solution(Points& x, const Points& old, double phi, double psi, const HalfEdge& a,
                             const HalfEdge& b, double reach) {
  Eigen::Matrix<double, 8, 3> rhs;
  const Constraints A = step5_constraints(phi, psi, a, b, rhs);
  Eigen::CompleteOrthogonalDecomposition<Constraints> cod;
  cod.setThreshold(1e-6);
  cod.compute(A);
  x = old + cod.solve(rhs - A.lazyProduct(old));
  if ((x - old).rowwise().norm().maxCoeff() > reach) return false;
  // Met when every constraint holds to a rounding-level share of the
  // points' scale, each row divided by its own coefficients: a tolerance
  // scaled by all of them together let a row with coefficients in the
  // thousands miss by 1e-9 edge lengths, and the edge by 0.02 rad.
  const Eigen::Matrix<double, 8, 3> miss = A.lazyProduct(x) - rhs;
  const double scale = old.norm() + rhs.norm();
  for (int i = 0; i < 8; ++i)
    if (miss.row(i).norm() > 1e-12 * A.row(i).norm() * scale) return false;
  return true;
}

// Along a macro half edge, M = (V, K, Y, Z) the edge row and L the next
// row on one side: the edge's derivative (quadratic, its Bernstein
// coefficients) and the cross differences towards L.
struct EdgeDerivatives {
  Point along[3], here[3];
};
EdgeDerivatives edge_derivatives(const Point* M, const Point* L) {
  return {{M[1] - M[0], M[2] - M[1], M[3] - M[2]}, {L[0] - M[0], L[1] - M[1], L[2] - M[2]}};
}

// Whether the patches on the two sides of a macro half edge fold onto one
// side of it somewhere between its ends: M = (V, K, Y, Z) the edge row, L
// and R the next rows on either side. The tangent planes agree there (Step
// 5), so a fold is a normal turned by π; decided exactly (normals_apart.h),
// however narrow. Where the vertex end itself folds (the sign condition
// fails at V), no move of Step 5 can mend it, and only s = ¼, ½, ¾ and Z
// are asked.
bool folds(const Point* M, const Point* L, const Point* R) {
  const auto [along, here] = edge_derivatives(M, L);
  const Point there[3] = {M[0] - R[0], M[1] - R[1], M[2] - R[2]};  // turned, so that apart is ≤ 0
  const Quartic n_here = cross_product(along, here), n_there = cross_product(along, there);
  if (n_here[0].dot(n_there[0]) > 0.0) return reaches_zero(n_here, n_there);
  for (const double t : {0.25, 0.5, 0.75, 1.0}) {
    const Point a = quadratic(along, t);
    if (a.cross(quadratic(here, t)).dot(a.cross(quadratic(there, t))) <= 0.0) return true;
  }
  return false;
}

// Whether the patch on one side of a macro half edge turns over between
// its ends: its normal along the edge (M the edge row, L the next row, as in
// folds) turns by π/2 or more from its normal at the vertex, which the
// vertex's tangent plane fixes. Both sides can turn over together, their
// tangent planes still agreeing — folds does not see that — when Step 5
// moves the point towards the centre O across the macro edge: on a scanned
// ellipsoid two nearly square pairs of triangles came out with normals
// turned by 179° at their diagonals' midpoints, dimples in the picture.
// Decided exactly, as folds; no call where the vertex's normal vanishes.
bool turns_back(const Point* M, const Point* L) {
  const auto [along, here] = edge_derivatives(M, L);
  const Quartic n = cross_product(along, here);
  if (n[0].isZero()) return false;
  return reaches_zero(n, Quartic{n[0], n[0], n[0], n[0], n[0]});
}

// Step 5 for the macro edge c of this side s (the other side t, its edge,
// runs the other way). `here` and `there` receive the moved points, each in
// its own side's orientation. Returns false when the constraints were
// dependent and could not all be met.
//
// The star at Z: the edges to O and O' join C¹ inside their macro triangles,
// so Z = (Y_a + Y_b)/2; the half edge to V_c ends in (Z − Y_a) + φ(Y_f − Y_a)
// + ψ(Y_g − Y_a) = 0 with (φ, ψ) fitted to the subdivided points, and then the
// half edge to V_c+1 must end in μ(φ, ψ), μ = −1/(1 + 2(φ + ψ)), for the two
// to share one tangent plane at Z. Y_f = (X_a + X_b)/2, Y_g likewise
// (Equation 9.10a on the edges to O, O').
bool join_macro_edge(const FaceSplit& s, int c, const FarSide& t, double max_move, EdgeSide& here, EdgeSide& there) {
  const int n = (c + 1) % 3;
  // The subdivided points, this side's macro edge as reference.
  const Point &z_old = s.Z[c], &ya_old = s.Ya[c], &yb_old = s.Yb[c], &yf_old = s.Y[c], &yg_old = t.Y;
  const Point u_old[6] = {ya_old, yb_old, s.Xa[c], s.Xb[c], t.Xb, t.Xa};  // Y_a, Y_b, X_a, X_b, X_a', X_b'
  Eigen::Vector2d at_Z_a = end_coefficients(z_old - ya_old, yf_old - ya_old, yg_old - ya_old);
  // Y_f and Y_g on one side of the edge (φψ ≤ 0) is a fold in the
  // subdivided patches themselves, as over a cap-shaped macro triangle; the
  // fit would keep it. Then the star is made C¹ instead: φ = ψ = −½, Z the
  // midpoint of Y_f and Y_g, with the halves' tangents in line (μ = 1). That
  // avoids the fold but is no G¹ join: with its constraints met to 5e-13 the
  // normals along such an edge of the demo's boundary differ by 0.17 rad, so
  // the edge is counted as joined approximately.
  const bool forced_star = !(at_Z_a.x() * at_Z_a.y() > 0.0);
  if (forced_star) at_Z_a = Eigen::Vector2d::Constant(-0.5);
  const double phi = at_Z_a.x(), psi = at_Z_a.y();
  const Eigen::Vector2d at_Z_b = -at_Z_a / (1.0 + 2.0 * (phi + psi));
  const HalfEdge a = half_edge(s.V[c], s.K[c], s.N[c], t.N_end, at_Z_a);
  const HalfEdge b = half_edge(s.V[n], s.Kn[c], s.N[n], t.N_start, at_Z_b);
  // Least displacement of the nine points under the eight constraints. The
  // three means are met by computing Z, Y_f, Y_g from u = (Y_a, Y_b, X_a,
  // X_b, X_a', X_b'), whose displacement δ then counts in the metric M = I +
  // ¼(three 2×2 blocks of ones). The other five rows B δ = r:
  const double B[5][6] = {
      {-(0.5 + phi + psi), 0.5, phi / 2.0, phi / 2.0, psi / 2.0, psi / 2.0},  // the star
      {2.0, 0.0, 2.0 * a.f0, 0.0, 2.0 * a.g0, 0.0},                          // (9.3b) towards V_c
      {a.y_c + 0.5, 0.5, 2.0 * a.f1 + a.f0 / 2.0, a.f0 / 2.0, 2.0 * a.g1 + a.g0 / 2.0, a.g0 / 2.0},  // (9.3c)
      {0.0, 2.0, 0.0, 2.0 * b.f0, 0.0, 2.0 * b.g0},                                                        // (9.3b) towards V_n
      {0.5, b.y_c + 0.5, b.f0 / 2.0, 2.0 * b.f1 + b.f0 / 2.0, b.g0 / 2.0, 2.0 * b.g1 + b.g0 / 2.0}};  // (9.3c)
  const Point c_rhs[5] = {Point::Zero(), a.rhs_b, a.rhs_c, b.rhs_b, b.rhs_c};
  const auto residual = [&](const Point* u, Point* r) {
    for (int i = 0; i < 5; ++i) {
      r[i] = c_rhs[i];
      for (int k = 0; k < 6; ++k) r[i] -= B[i][k] * u[k];
    }
  };
  Point r[5];
  residual(u_old, r);
  // Closed form. Rows 1 and 3 give δY_a = r1/2 − f0 δX_a − g0 δX_a' and δY_b
  // likewise; the three others then read R δX = s on δX = (δX_a, δX_b,
  // δX_a', δX_b'), a 3×4 system with one null vector n (its signed 3×3
  // minors). δ = (a solution with the unknown of the largest |n_k| kept, by
  // the inverse of the other three columns) + n·t, t the least-M-displacement
  // multiple. The constraints are dependent when n is short against the rows.
  const double a_of[4] = {a.f0, 0.0, a.g0, 0.0}, b_of[4] = {0.0, b.f0, 0.0, b.g0};  // δY_a, δY_b on δX
  static constexpr int reduced_rows[3] = {0, 2, 4};
  double R[3][4];
  for (int i = 0; i < 3; ++i) {
    const double* row = B[reduced_rows[i]];
    for (int k = 0; k < 4; ++k) R[i][k] = row[2 + k] - row[0] * a_of[k] - row[1] * b_of[k];
  }
  const auto column = [&R](int k) { return Eigen::Vector3d(R[0][k], R[1][k], R[2][k]); };
  const Eigen::Vector3d col[4] = {column(0), column(1), column(2), column(3)};
  double null[4];
  for (int k = 0; k < 4; ++k) {
    int other[3], m = 0;
    for (int j = 0; j < 4; ++j)
      if (j != k) other[m++] = j;
    null[k] = ((k % 2 == 0) ? 1.0 : -1.0) * col[other[0]].dot(col[other[1]].cross(col[other[2]]));
  }
  double row_norms = 1.0, null_norm = 0.0;
  for (int i = 0; i < 3; ++i) row_norms *= std::sqrt(R[i][0] * R[i][0] + R[i][1] * R[i][1] + R[i][2] * R[i][2] + R[i][3] * R[i][3]);
  for (int k = 0; k < 4; ++k) null_norm += null[k] * null[k];
  null_norm = std::sqrt(null_norm);

  const Point old[unknowns] = {z_old, ya_old, yb_old, yf_old, yg_old, u_old[2], u_old[3], u_old[4], u_old[5]};
  const double reach = std::min(kReach, max_move) * (s.V[n] - s.V[c]).norm();
  Point x[unknowns];
  bool met = false;
  if (null_norm > 1e-12 * row_norms) {
    int kept = 0;
    for (int k = 1; k < 4; ++k)
      if (std::abs(null[k]) > std::abs(null[kept])) kept = k;
    int other[3], m = 0;
    for (int j = 0; j < 4; ++j)
      if (j != kept) other[m++] = j;
    const Eigen::Vector3d &c0 = col[other[0]], &c1 = col[other[1]], &c2 = col[other[2]];
    Eigen::Vector3d inverse_rows[3] = {c1.cross(c2), c2.cross(c0), c0.cross(c1)};
    const double det = c0.dot(inverse_rows[0]);
    for (Eigen::Vector3d& row : inverse_rows) row /= det;
    const double nu[6] = {-a.f0 * null[0] - a.g0 * null[2], -b.f0 * null[1] - b.g0 * null[3], null[0], null[1], null[2], null[3]};
    double nn = 0.0;
    for (int k = 0; k < 6; k += 2) {
      const double pair = nu[k] + nu[k + 1];
      nn += nu[k] * nu[k] + nu[k + 1] * nu[k + 1] + pair * pair / 4.0;
    }
    // The least-M-displacement δ with B δ = r, added to u.
    const auto add_correction = [&](const Point* r, Point* u) {
      Point rs[3];
      for (int i = 0; i < 3; ++i) {
        const double* row = B[reduced_rows[i]];
        rs[i] = r[reduced_rows[i]] - row[0] * (r[1] / 2.0) - row[1] * (r[3] / 2.0);
      }
      Point delta[6];
      delta[2 + kept] = Point::Zero();
      for (int j = 0; j < 3; ++j)
        delta[2 + other[j]] = inverse_rows[j][0] * rs[0] + inverse_rows[j][1] * rs[1] + inverse_rows[j][2] * rs[2];
      delta[0] = r[1] / 2.0 - a.f0 * delta[2] - a.g0 * delta[4];
      delta[1] = r[3] / 2.0 - b.f0 * delta[3] - b.g0 * delta[5];
      Point nd = Point::Zero();
      for (int k = 0; k < 6; k += 2)
        nd += nu[k] * delta[k] + nu[k + 1] * delta[k + 1] + ((nu[k] + nu[k + 1]) / 4.0) * (delta[k] + delta[k + 1]);
      const Point multiple = -nd / nn;
      for (int k = 0; k < 6; ++k) u[k] += delta[k] + nu[k] * multiple;
    };
    // Solved, then refined once on the residual (as rounding in R's inverse
    // grows with its condition).
    Point u[6];
    std::copy(u_old, u_old + 6, u);
    add_correction(r, u);
    residual(u, r);
    add_correction(r, u);
    x[Ya] = u[0], x[Yb] = u[1], x[Xa] = u[2], x[Xb] = u[3], x[Xa_there] = u[4], x[Xb_there] = u[5];
    x[Z] = (u[0] + u[1]) / 2.0;
    x[Yf] = (u[2] + u[3]) / 2.0;
    x[Yg] = (u[4] + u[5]) / 2.0;
    double moved = 0.0;
    for (int k = 0; k < unknowns; ++k) moved = std::max(moved, (x[k] - old[k]).squaredNorm());
    met = moved <= reach * reach;
  }
  // Where the constraints cannot be met within reach: the damped step on u
  // alone, Z, Y_f and Y_g kept the means of their pairs, so that the inner
  // edges to O and O' stay C¹ (Steps 6–7 need no more) and only the macro
  // edge itself is joined approximately. (Damping all eight rows, the means
  // among them, let the inner edges crease as well.)
  const auto damped = [&](double bound) {
    static const Eigen::Matrix<double, unknowns, 6> moved = [] {
      Eigen::Matrix<double, unknowns, 6> D = Eigen::Matrix<double, unknowns, 6>::Zero();
      D(Z, 0) = D(Z, 1) = D(Yf, 2) = D(Yf, 3) = D(Yg, 4) = D(Yg, 5) = 0.5;
      D(Ya, 0) = D(Yb, 1) = D(Xa, 2) = D(Xb, 3) = D(Xa_there, 4) = D(Xb_there, 5) = 1.0;
      return D;
    }();
    Point r0[5];
    residual(u_old, r0);
    Eigen::Matrix<double, 5, 6> Bm;
    Eigen::Matrix<double, 5, 3> rm;
    for (int i = 0; i < 5; ++i) {
      for (int k = 0; k < 6; ++k) Bm(i, k) = B[i][k];
      rm.row(i) = r0[i].transpose();
    }
    const Eigen::Matrix<double, 6, 3> step = damped_step(Bm, rm, bound, moved);
    for (int k = 0; k < unknowns; ++k) x[k] = old[k] + (moved.row(k) * step).transpose();
  };
  if (!met) {
    Points old_rows, x_rows;
    for (int k = 0; k < unknowns; ++k) old_rows.row(k) = old[k].transpose();
    met = pseudo_inverse_solution(x_rows, old_rows, phi, psi, a, b, reach);
    if (met)
      for (int k = 0; k < unknowns; ++k) x[k] = x_rows.row(k).transpose();
    else
      damped(reach);
  }
  // A fold left where the constraints were met needs a vertex whose own
  // coefficients fold ((9.3a) with f0 g0 < 0, the sign condition failing);
  // a damped join may fold anywhere. The patches then share their tangent
  // planes with normals turned by π, a spike in the picture: the damped
  // step takes over, with the largest move halved from half an edge length
  // until the fold is gone — not G¹ there, and counted.
  const auto folded = [&](bool or_turned) {
    const Point Ma[4] = {s.V[c], s.K[c], x[Ya], x[Z]}, La[3] = {s.N[c], x[Xa], x[Yf]},
                Ra[3] = {t.N_end, x[Xa_there], x[Yg]};
    const Point Mb[4] = {s.V[n], s.Kn[c], x[Yb], x[Z]}, Lb[3] = {s.N[n], x[Xb], x[Yf]},
                Rb[3] = {t.N_start, x[Xb_there], x[Yg]};
    return folds(Ma, La, Ra) || folds(Mb, Lb, Rb) || (or_turned && (turns_back(Ma, La) || turns_back(Mb, Lb)));
  };
  const double length = (s.V[n] - s.V[c]).norm();
  if (folded(false)) {
    met = false;
    for (double bound = kFoldReach * length; bound >= kFoldReach * length / 64.0; bound /= 2.0) {
      damped(bound);
      if (!folded(false)) break;
    }
  } else if (std::isfinite(max_move) && folded(true)) {
    // Turned over, not apart: with the moves bounded (a bulge is not
    // wanted), the same damped steps, kept only where one mends it (else the
    // exact join stands, G¹ if turned over). Unbounded, as the thesis, every
    // G¹ join stands: on bunny00 0.3% of the patches along macro edges turn over so.
    Point exact[unknowns];
    std::copy(x, x + unknowns, exact);
    bool mended = false;
    for (double bound = kFoldReach * length; bound >= kFoldReach * length / 64.0 && !mended; bound /= 2.0) {
      damped(bound);
      mended = !folded(true);
    }
    if (mended)
      met = false;
    else
      std::copy(exact, exact + unknowns, x);
  }
  here = {x[Z], x[Ya], x[Yb], x[Yf], x[Xa], x[Xb]};
  there = {x[Z], x[Yb], x[Ya], x[Yg], x[Xb_there], x[Xa_there]};
  return met && !forced_star && a.end_fits && b.end_fits;
}

// The six micro triangles of one macro triangle from its split and its three
// edges after Step 5, with Steps 6 and 7: Q at the vertex edges from Equation
// (9.13a), at the midpoint edges the mean of their neighbours (9.12a), O =
// (Q0 + Q2 + Q4)/3 — the domain ratios of the split, so the interior joins C¹.
void assemble(const FaceSplit& s, const EdgeSide* const* e, CubicTriangle* patch) {
  Point Q[6];
  for (int c = 0; c < 3; ++c) {  // edges V_c → O
    const Point& N = s.N[c];
    Q[2 * c] = N + 2.0 / 3.0 * (e[c]->Xa + e[(c + 2) % 3]->Xb - 2.0 * N);
  }
  for (int j = 1; j < 6; j += 2) Q[j] = (Q[j - 1] + Q[(j + 1) % 6]) / 2.0;  // edges Z_c → O
  const Point O = (Q[0] + Q[2] + Q[4]) / 3.0;
  for (int c = 0; c < 3; ++c) {
    const int n = (c + 1) % 3;
    CubicTriangle& a = patch[2 * c];  // (V_c, Z_c, O)
    a[A_corner] = s.V[c];
    a[outer_near_A] = s.K[c];
    a[AO_near_A] = s.N[c];
    a[outer_near_B] = e[c]->Ya;
    a[centre] = e[c]->Xa;
    a[AO_near_O] = Q[2 * c];
    a[B_corner] = e[c]->Z;
    a[BO_near_B] = e[c]->Y;
    a[BO_near_O] = Q[2 * c + 1];
    a[O_corner] = O;
    CubicTriangle& b = patch[2 * c + 1];  // (Z_c, V_n, O)
    b[A_corner] = e[c]->Z;
    b[outer_near_A] = e[c]->Yb;
    b[AO_near_A] = e[c]->Y;
    b[outer_near_B] = s.Kn[c];
    b[centre] = e[c]->Xb;
    b[AO_near_O] = Q[2 * c + 1];
    b[B_corner] = s.V[n];
    b[BO_near_B] = s.N[n];
    b[BO_near_O] = Q[(2 * c + 2) % 6];
    b[O_corner] = O;
  }
}

// Page faults on the fresh patch memory cost about as much as building the
// patches on the measured machine (a virtual machine, one fault per 4 KiB).
// Linux ≥ 5.14 maps a whole range in one call; elsewhere (and on older
// kernels, which refuse the advice) the pages fault in as they are written.
void prefault(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  constexpr std::uintptr_t page = 4096;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + page - 1) & ~(page - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(page - 1);
  if (begin < end) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)data, (void)bytes;
#endif
}

// Copies one macro triangle's six finished patches (1440 bytes, built in a
// local buffer) to their place in the surface. Past the caches the patch
// memory is only written here, so non-temporal stores skip reading each line
// before writing it (half the memory traffic) and leave the caches to the
// mesh; the patches are contiguous, so the stores fill whole lines.
void store_patches(const CubicTriangle* from, CubicTriangle* to) {
  constexpr std::size_t values = 6 * sizeof(CubicTriangle) / sizeof(double);
#if defined(__SSE2__)
  static_assert(sizeof(CubicTriangle) % 16 == 0, "patches stay 16-byte aligned");
  const double* source = from->front().data();
  double* target = to->front().data();
  if (reinterpret_cast<std::uintptr_t>(target) % 16 == 0) {
    for (std::size_t i = 0; i < values; i += 2) _mm_stream_pd(target + i, _mm_load_pd(source + i));
    return;
  }
#endif
  std::copy(from, from + 6, to);
  (void)values;
}

}  // namespace

BezierSurface six_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                        const MeshEdges& edges, double tension, double max_move) {
  BezierSurface surface;
  six_split(V, F, N, edges, tension, surface, max_move);
  return surface;
}

void six_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N, const MeshEdges& edges,
               double tension, BezierSurface& surface, double max_move) {
  // One pass over the macro triangles, each written once, complete. Face f
  // solves Step 5 on its edges to faces g > f and leaves g's side of the
  // result for g; its edges to g < f were solved when g came.
  const Eigen::Index faces = F.rows();
  surface.patches.clear();
  surface.macro.clear();
  surface.dependent_edges.clear();
  if (surface.patches.capacity() < std::size_t(6 * faces)) {
    surface.patches = {};  // no copy of the old patches on growth
    surface.patches.reserve(6 * faces);
    prefault(surface.patches.data(), surface.patches.capacity() * sizeof(CubicTriangle));
  }
  // The sides left for later faces wait in entries that are reused once read:
  // only the edges between the faces done and those to come are held, so the
  // entries stay few and in the caches when the faces come in a local order.
  // Default-initialised (not zeroed): every entry is written before it is read.
  std::vector<EdgeSide, UninitialisedAllocator<EdgeSide>> left_for_later;
  std::vector<int> free_entries;
  const std::unique_ptr<int[]> slot(new int[3 * faces]);  // half edge 3g + d → its entry in left_for_later
  FaceSplit own;
  EdgeSide here[3];
  const EdgeSide* sides[3];
  alignas(16) CubicTriangle local[6];
  surface.patches.resize(6 * faces);  // not written here (UninitialisedAllocator)
  surface.macro.resize(6 * faces);
  for (int f = 0; f < faces; ++f) {
    split_face(macro_patch(V, F, N, f, tension), own);
    for (int c = 0; c < 3; ++c) {
      const int g = edges.neighbour(f, c), d = edges.neighbour_edge(f, c);
      if (g > f) {
        int entry;
        if (free_entries.empty()) {
          entry = static_cast<int>(left_for_later.size());
          left_for_later.emplace_back();
        } else {
          entry = free_entries.back();
          free_entries.pop_back();
        }
        slot[3 * g + d] = entry;
        if (!join_macro_edge(own, c, far_side(macro_patch(V, F, N, g, tension), d), max_move, here[c], left_for_later[static_cast<std::size_t>(entry)]))
          surface.dependent_edges.push_back({f, g});
      }
    }
    for (int c = 0; c < 3; ++c)
      sides[c] = edges.neighbour(f, c) > f ? &here[c] : &left_for_later[static_cast<std::size_t>(slot[3 * f + c])];
    assemble(own, sides, local);
    for (int c = 0; c < 3; ++c)
      if (edges.neighbour(f, c) < f) free_entries.push_back(slot[3 * f + c]);
    store_patches(local, &surface.patches[6 * f]);
    std::fill_n(&surface.macro[6 * f], 6, f);
  }
#if defined(__SSE2__)
  _mm_sfence();  // the streamed stores visible before the surface is used
#endif
}

}  // namespace scanstation
