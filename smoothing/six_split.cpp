#include "smoothing/six_split.h"

#include "smoothing/macro_patches.h"
#include "smoothing/tangent_plane_condition.h"

#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>

namespace scanstation {

namespace {

// Control points of a micro triangle (A, B, O): A = b300, B = b030, O = b003.
constexpr int A_corner = control_index(3, 0, 0), B_corner = control_index(0, 3, 0), O_corner = control_index(0, 0, 3);
constexpr int outer_near_A = control_index(2, 1, 0), outer_near_B = control_index(1, 2, 0);
constexpr int AO_near_A = control_index(2, 0, 1), AO_near_O = control_index(1, 0, 2);
constexpr int BO_near_B = control_index(0, 2, 1), BO_near_O = control_index(0, 1, 2);
constexpr int centre = control_index(1, 1, 1);

// Step 0: N − V = τ((K0 − V) + (K1 − V)) at the macro vertices, τ = 2/3.
constexpr double vertex_edge_ratio = 2.0 / 3.0;

// Step 4: subdivision into six (s[2c] = (V_c, Z_c, O), s[2c+1] = (Z_c, V_c+1,
// O)), and N on the edges from the vertices to O by Equation (9.14). The
// control points are blossom values P[r_a, r_b, r_c] of the corners, edge
// midpoints Z_c and centroid O, each a fixed combination of the ten macro
// control points; only those read before Steps 5–7 set them are computed,
// eight per macro edge c: Z_c, K = P[V_c, V_c, Z_c], P[V_c+1, V_c+1, Z_c],
// Y = P[Z_c, Z_c, V_c], P[Z_c, Z_c, V_c+1], Y_f = P[Z_c, Z_c, O] and the
// centres P[V_c, Z_c, O], P[Z_c, V_c+1, O].
using SplitWeights = Eigen::Matrix<double, 24, 10, Eigen::RowMajor>;

const SplitWeights& split_weights() {
  static const SplitWeights weights = [] {
    std::array<Barycentric, 7> r;  // corners 0–2, edge midpoints 3–5 (edge c is 3 + c), centroid 6
    for (int c = 0; c < 3; ++c) {
      r[c] = Barycentric::Unit(c);
      r[3 + c] = (Barycentric::Unit(c) + Barycentric::Unit((c + 1) % 3)) / 2.0;
    }
    r[6] = Barycentric::Constant(1.0 / 3.0);
    SplitWeights w;
    for (int i = 0; i < 10; ++i) {
      CubicTriangle unit;
      for (Eigen::Vector3d& p : unit) p.setZero();
      unit[i].x() = 1.0;
      const auto blossom = [&](int a, int b, int c) {
        return blossom_level(blossom_level(blossom_level(unit, r[a]), r[b]), r[c]).x();
      };
      for (int c = 0; c < 3; ++c) {
        const int V = c, next = (c + 1) % 3, Zc = 3 + c, O = 6;
        const int rows[8][3] = {{Zc, Zc, Zc}, {V, V, Zc},  {next, next, Zc}, {Zc, Zc, V},
                                {Zc, Zc, next}, {Zc, Zc, O}, {V, Zc, O},        {Zc, next, O}};
        for (int k = 0; k < 8; ++k) w(8 * c + k, i) = blossom(rows[k][0], rows[k][1], rows[k][2]);
      }
    }
    return w;
  }();
  return weights;
}

void split_in_six(const CubicTriangle& macro, CubicTriangle* s) {
  Eigen::Matrix<double, 10, 3> net;
  for (int i = 0; i < 10; ++i) net.row(i) = macro[i].transpose();
  const Eigen::Matrix<double, 24, 3> value = split_weights().lazyProduct(net);
  for (int c = 0; c < 3; ++c) {
    const int next = (c + 1) % 3;
    const auto point = [&](int k) -> Eigen::Vector3d { return value.row(8 * c + k).transpose(); };
    CubicTriangle& a = s[2 * c];
    CubicTriangle& b = s[2 * c + 1];
    a[A_corner] = macro[control_index(c == 0 ? 3 : 0, c == 1 ? 3 : 0, c == 2 ? 3 : 0)];
    b[B_corner] = macro[control_index(next == 0 ? 3 : 0, next == 1 ? 3 : 0, next == 2 ? 3 : 0)];
    a[B_corner] = b[A_corner] = point(0);
    a[outer_near_A] = point(1);
    b[outer_near_B] = point(2);
    a[outer_near_B] = point(3);
    b[outer_near_A] = point(4);
    a[BO_near_B] = b[AO_near_A] = point(5);
    a[centre] = point(6);
    b[centre] = point(7);
  }
  for (int c = 0; c < 3; ++c) {
    CubicTriangle& after = s[2 * c];
    CubicTriangle& before = s[(2 * c + 5) % 6];
    const Eigen::Vector3d& V = after[A_corner];
    const Eigen::Vector3d N = V + vertex_edge_ratio * ((after[outer_near_A] - V) + (before[outer_near_B] - V));
    after[AO_near_A] = N;
    before[BO_near_B] = N;
  }
}

// Unknowns of Step 5, one row each.
enum Unknown { Z, Ya, Yb, Yf, Yg, Xa, Xb, Xa_there, Xb_there, unknowns };
using Constraints = Eigen::Matrix<double, 8, unknowns>;
using Points = Eigen::Matrix<double, unknowns, 3>;

// Equation (9.3b, c) on the half edge V → Z with M = (V, K, Y, Z), rows
// L = (N_here, X_here, Y_f), R = (N_there, X_there, Y_g); E, F, G linear
// from (1, f0, g0) at V (Equation 9.3a) to `at_Z` = (1, f1, g1) at Z.
void half_edge_rows(Constraints& A, Eigen::Matrix<double, 8, 3>& rhs, int row, Unknown Y, Unknown X_here,
                    Unknown X_there, const Eigen::Vector3d& V, const Eigen::Vector3d& K, const Eigen::Vector3d& N_here,
                    const Eigen::Vector3d& N_there, const Eigen::Vector2d& at_Z) {
  const Eigen::Vector2d c0 = end_coefficients(K - V, N_here - V, N_there - V);
  const double f0 = c0.x(), g0 = c0.y(), f1 = at_Z.x(), g1 = at_Z.y();
  // (9.3b): (K − V) + 2(Y − K) + f1(N_here − V) + 2f0(X_here − K) + g1(N_there − V) + 2g0(X_there − K) = 0
  A(row, Y) = 2.0;
  A(row, X_here) = 2.0 * f0;
  A(row, X_there) = 2.0 * g0;
  rhs.row(row) = (-(K - V) + 2.0 * K - f1 * (N_here - V) - g1 * (N_there - V) + 2.0 * (f0 + g0) * K).transpose();
  // (9.3c): 2(Y − K) + (Z − Y) + 2f1(X_here − K) + f0(Y_f − Y) + 2g1(X_there − K) + g0(Y_g − Y) = 0
  A(row + 1, Y) = 1.0 - f0 - g0;
  A(row + 1, Z) = 1.0;
  A(row + 1, X_here) = 2.0 * f1;
  A(row + 1, X_there) = 2.0 * g1;
  A(row + 1, Yf) = f0;
  A(row + 1, Yg) = g0;
  rhs.row(row + 1) = (2.0 * (1.0 + f1 + g1) * K).transpose();
}

// Step 5 for the macro edge between s[2c], s[2c+1] (this side) and t[2d],
// t[2d+1] (the other side). Returns false when the constraints were
// dependent and could not all be met.
//
// The star at Z: the edges to O and O' join C¹ inside their macro triangles,
// so Z = (Y_a + Y_b)/2; the half edge to V_c ends in (Z − Y_a) + φ(Y_f − Y_a)
// + ψ(Y_g − Y_a) = 0 with (φ, ψ) fitted to the subdivided points, and then the
// half edge to V_c+1 must end in μ(φ, ψ), μ = −1/(1 + 2(φ + ψ)), for the two
// to share one tangent plane at Z.
bool join_macro_edge(CubicTriangle& sa, CubicTriangle& sb, CubicTriangle& tb, CubicTriangle& ta) {
  Points old;
  old.row(Z) = sa[B_corner].transpose();
  old.row(Ya) = sa[outer_near_B].transpose();
  old.row(Yb) = sb[outer_near_A].transpose();
  old.row(Yf) = sa[BO_near_B].transpose();
  old.row(Yg) = ta[AO_near_A].transpose();
  old.row(Xa) = sa[centre].transpose();
  old.row(Xb) = sb[centre].transpose();
  old.row(Xa_there) = ta[centre].transpose();
  old.row(Xb_there) = tb[centre].transpose();
  const Eigen::Vector3d z = old.row(Z), ya = old.row(Ya);
  const Eigen::Vector2d at_Z_a = end_coefficients(z - ya, Eigen::Vector3d(old.row(Yf)) - ya, Eigen::Vector3d(old.row(Yg)) - ya);
  const double phi = at_Z_a.x(), psi = at_Z_a.y();
  const Eigen::Vector2d at_Z_b = -at_Z_a / (1.0 + 2.0 * (phi + psi));
  Constraints A = Constraints::Zero();
  Eigen::Matrix<double, 8, 3> rhs = Eigen::Matrix<double, 8, 3>::Zero();
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
  half_edge_rows(A, rhs, 4, Ya, Xa, Xa_there, sa[A_corner], sa[outer_near_A], sa[AO_near_A], ta[BO_near_B], at_Z_a);
  half_edge_rows(A, rhs, 6, Yb, Xb, Xb_there, sb[B_corner], sb[outer_near_B], sb[BO_near_B], tb[AO_near_A], at_Z_b);
  // Least displacement under A x = rhs. Rows 0, 2, 3 only say that Z, Y_f and
  // Y_g are means of two other unknowns: they are met exactly by computing
  // them as such from u = (Y_a, Y_b, X_a, X_b, X_a', X_b'), in which the
  // displacement is |δu|²_M with M = I + ¼(three 2×2 blocks of ones), a
  // constant metric. The five other rows become B u = c, solved for the
  // least M-displacement, refined once. Dependent constraints (a vanishing
  // pivot, e.g. on symmetric configurations) go through the pseudo-inverse
  // instead.
  static constexpr int rows[5] = {1, 4, 5, 6, 7};
  static constexpr int free_unknown[6] = {Ya, Yb, Xa, Xb, Xa_there, Xb_there};
  static constexpr int mean_of[6] = {Z, Z, Yf, Yf, Yg, Yg};  // the mean each free unknown enters
  Eigen::Matrix<double, 5, 6> B;
  Eigen::Matrix<double, 5, 3> c;
  for (int r = 0; r < 5; ++r) {
    for (int u = 0; u < 6; ++u) B(r, u) = A(rows[r], free_unknown[u]) + 0.5 * A(rows[r], mean_of[u]);
    c.row(r) = rhs.row(rows[r]);
  }
  // With δu = M^-½ w the problem is min |w| under C w = r, C = B M^-½ (M^-½
  // block-diagonal with blocks [[p, q], [q, p]]); C = L Q by Gram–Schmidt on
  // the rows, twice, so Q's rows are orthonormal to rounding and the
  // condition number is not squared: w = Qᵀ L⁻¹ r. By hand: Eigen's general
  // kernels cost more than the arithmetic at this size.
  const double p = (std::sqrt(2.0 / 3.0) + 1.0) / 2.0, q = (std::sqrt(2.0 / 3.0) - 1.0) / 2.0;
  Eigen::Matrix<double, 5, 6, Eigen::RowMajor> Q;
  for (int k = 0; k < 6; k += 2) {
    Q.col(k) = p * B.col(k) + q * B.col(k + 1);
    Q.col(k + 1) = q * B.col(k) + p * B.col(k + 1);
  }
  double L[5][5] = {};
  for (int i = 0; i < 5; ++i) {
    for (int pass = 0; pass < 2; ++pass)
      for (int j = 0; j < i; ++j) {
        const double projection = Q.row(j).dot(Q.row(i));
        L[i][j] += projection;
        Q.row(i) -= projection * Q.row(j);
      }
    L[i][i] = Q.row(i).norm();
    if (L[i][i] > 0.0) Q.row(i) /= L[i][i];
  }
  double largest_pivot = 0.0, smallest_pivot = INFINITY;
  for (int i = 0; i < 5; ++i) {
    largest_pivot = std::max(largest_pivot, L[i][i]);
    smallest_pivot = std::min(smallest_pivot, L[i][i]);
  }
  const auto correction = [&](Eigen::Matrix<double, 5, 3> r) -> Eigen::Matrix<double, 6, 3> {
    for (int i = 0; i < 5; ++i) {
      for (int k = 0; k < i; ++k) r.row(i) -= L[i][k] * r.row(k);
      r.row(i) /= L[i][i];
    }
    const Eigen::Matrix<double, 6, 3> w = Q.transpose().lazyProduct(r);
    Eigen::Matrix<double, 6, 3> delta;
    for (int k = 0; k < 6; k += 2) {
      delta.row(k) = p * w.row(k) + q * w.row(k + 1);
      delta.row(k + 1) = q * w.row(k) + p * w.row(k + 1);
    }
    return delta;
  };
  Eigen::Matrix<double, 6, 3> u_old, u;
  for (int k = 0; k < 6; ++k) u_old.row(k) = old.row(free_unknown[k]);
  const auto expand = [](const Eigen::Matrix<double, 6, 3>& free) {
    Points x;
    for (int k = 0; k < 6; ++k) x.row(free_unknown[k]) = free.row(k);
    x.row(Z) = (free.row(0) + free.row(1)) / 2.0;
    x.row(Yf) = (free.row(2) + free.row(3)) / 2.0;
    x.row(Yg) = (free.row(4) + free.row(5)) / 2.0;
    return x;
  };
  // Exact solution unless the constraints are (nearly) dependent, which
  // shows as a vanishing pivot or as control points thrown further than the
  // macro edge is long; then the closest point of the well-posed part
  // (pseudo-inverse, small singular values dropped): bounded, not G¹, and
  // counted.
  const double reach = 100.0 * (sb[B_corner] - sa[A_corner]).norm();
  Points x = old;
  bool met = false;
  if (smallest_pivot > 1e-9 * largest_pivot) {
    u = u_old;
    for (int step = 0; step < 2; ++step) u += correction(c - B.lazyProduct(u));
    x = expand(u);
    met = (x - old).rowwise().norm().maxCoeff() <= reach;
  }
  if (!met) {
    Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix<double, 8, unknowns>> cod;
    cod.setThreshold(1e-6);
    cod.compute(A);
    x = old + cod.solve(rhs - A.lazyProduct(old));
    met = (A.lazyProduct(x) - rhs).norm() <= 1e-10 * (rhs.norm() + A.lazyProduct(old).norm() + old.norm()) &&
          (x - old).rowwise().norm().maxCoeff() <= reach;
  }
  const Eigen::Vector3d new_z = x.row(Z);
  sa[B_corner] = sb[A_corner] = tb[B_corner] = ta[A_corner] = new_z;
  sa[outer_near_B] = ta[outer_near_A] = x.row(Ya).transpose();
  sb[outer_near_A] = tb[outer_near_B] = x.row(Yb).transpose();
  sa[BO_near_B] = sb[AO_near_A] = x.row(Yf).transpose();
  tb[BO_near_B] = ta[AO_near_A] = x.row(Yg).transpose();
  sa[centre] = x.row(Xa).transpose();
  sb[centre] = x.row(Xb).transpose();
  ta[centre] = x.row(Xa_there).transpose();
  tb[centre] = x.row(Xb_there).transpose();
  return met;
}

// Steps 6 and 7 inside one macro triangle: the domain ratios of the split.
void join_star(CubicTriangle* s) {
  Eigen::Vector3d Q[6];
  for (int j = 0; j < 6; j += 2) {  // edges V → O, Equation (9.13a)
    const Eigen::Vector3d N = s[j][AO_near_A];
    Q[j] = N + 2.0 / 3.0 * (s[j][centre] + s[(j + 5) % 6][centre] - 2.0 * N);
  }
  for (int j = 1; j < 6; j += 2) Q[j] = (Q[j - 1] + Q[(j + 1) % 6]) / 2.0;  // edges Z → O, (9.12a)
  const Eigen::Vector3d O = (Q[0] + Q[2] + Q[4]) / 3.0;
  for (int j = 0; j < 6; ++j) {
    s[j][AO_near_O] = Q[j];
    s[(j + 5) % 6][BO_near_O] = Q[j];
    s[j][O_corner] = O;
  }
}

}  // namespace

BezierSurface six_split(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N,
                        const MeshEdges& edges, double tension) {
  BezierSurface surface;
  surface.patches.resize(6 * F.rows());
  surface.macro.resize(6 * F.rows());
  for (int f = 0; f < F.rows(); ++f) {
    split_in_six(macro_patch(V, F, N, f, tension), &surface.patches[6 * f]);
    for (int j = 0; j < 6; ++j) surface.macro[6 * f + j] = f;
  }
  auto& P = surface.patches;
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int g = edges.neighbour(f, c), d = edges.neighbour_edge(f, c);
      if (f < g && !join_macro_edge(P[6 * f + 2 * c], P[6 * f + 2 * c + 1], P[6 * g + 2 * d], P[6 * g + 2 * d + 1]))
        ++surface.dependent_edges;
    }
  for (int f = 0; f < F.rows(); ++f) join_star(&P[6 * f]);
  return surface;
}

}  // namespace scanstation
