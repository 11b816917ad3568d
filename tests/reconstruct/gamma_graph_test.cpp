// γ-neighborhood graph: fast code against the brute force of Definitions
// 3.1–3.3, the reductions of §3.2, Lemmas 3.1–3.3, invariances, degeneracies.
#include "reconstruct/gamma_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include "core/errors.h"
#include "reconstruct/gamma_brute_force.h"
#include "test_support.h"

namespace scanstation {
namespace {

template <int D>
using Rows = std::vector<std::array<int, D>>;

template <int D>
Rows<D> rows(const Eigen::Matrix<int, Eigen::Dynamic, D>& M) {
  Rows<D> out(M.rows());
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (int j = 0; j < D; ++j) out[i][j] = M(i, j);
  return out;
}

template <int D>
Eigen::Matrix<double, Eigen::Dynamic, D> random_points(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Matrix<double, Eigen::Dynamic, D> V(n, D);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < D; ++j) V(i, j) = u(rng);
  return V;
}

template <int D>
Rows<D> fast(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, double c0, double c1) {
  return rows<D>(gamma_graph(V, c0, c1));
}
template <int D>
Rows<D> fast(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const GammaRange& g) {
  return rows<D>(gamma_graph(V, g));
}

template <int D>
bool subset(const Rows<D>& a, const Rows<D>& b) {
  return std::includes(b.begin(), b.end(), a.begin(), a.end());
}

template <int D>
Rows<D> merged(const Rows<D>& a, const Rows<D>& b) {
  Rows<D> out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

// Parameters avoid accidental ties except the exact ones -1, 0, 1.
const std::vector<double> kGrid{-1, -0.83, -0.5, -0.21, 0, 0.17, 0.5, 0.77, 1};

template <int D>
void expect_fixed_matches_brute(int n, unsigned seeds) {
  for (unsigned seed = 0; seed < seeds; ++seed) {
    const auto V = random_points<D>(n, seed);
    for (double c1 : kGrid)
      for (double c0 : kGrid)
        if (std::abs(c0) <= std::abs(c1)) {
          ASSERT_EQ(fast<D>(V, c0, c1), test::brute_gamma<D>(V, c0, c1))
              << "seed " << seed << " c0 " << c0 << " c1 " << c1;
        }
  }
}

TEST(GammaGraph, FixedParameters2DMatchBruteForce) { expect_fixed_matches_brute<2>(18, 25); }
TEST(GammaGraph, FixedParameters3DMatchBruteForce) { expect_fixed_matches_brute<3>(13, 8); }

// Negative parameters take the direct lens queries (not the profiles) in
// the fixed form: on the surface samples a scan gives (a noisy sphere, where
// most triangles have an empty lens) and on a lattice full of co-spherical
// and coplanar points, they agree with the brute force.
TEST(GammaGraph, NegativeParametersOnSurfaceSamplesAndALatticeMatchBruteForce) {
  std::vector<Eigen::MatrixX3d> inputs;
  for (unsigned seed = 0; seed < 3; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    Eigen::MatrixX3d V(22, 3);
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
      const Eigen::Vector3d p(g(rng), g(rng), g(rng));
      V.row(i) = (p.normalized() * (1.0 + 0.01 * g(rng))).transpose();
    }
    inputs.push_back(V);
  }
  Eigen::MatrixX3d lattice(18, 3);
  for (int i = 0; i < 18; ++i) lattice.row(i) << i % 3, (i / 3) % 3, i / 9;
  inputs.push_back(lattice);
  for (std::size_t k = 0; k < inputs.size(); ++k)
    for (double c1 : {-0.83, -0.5, -0.21})
      for (double c0 : {-0.21, 0.0, 0.17, -c1}) {
        if (std::abs(c0) > std::abs(c1)) continue;
        ASSERT_EQ(fast<3>(inputs[k], c0, c1), test::brute_gamma<3>(inputs[k], c0, c1))
            << "input " << k << " c0 " << c0 << " c1 " << c1;
      }
}

// Definition 3.3: every simplex's (c'0, c'1) and the range graphs.
template <int D>
void expect_values_match_brute(int n, unsigned seeds) {
  for (unsigned seed = 100; seed < 100 + seeds; ++seed) {
    const auto V = random_points<D>(n, seed);
    Eigen::Matrix<int, Eigen::Dynamic, D> S;
    Eigen::MatrixX2d C;
    gamma_values(V, -1.0, S, C);
    Rows<D> expected;
    for (const auto& row : test::all_subsets<D>(n)) {
      const auto c = test::brute_largest<D>(test::brute_case<D>(V, row));
      if (!c) continue;
      expected.push_back(row);
    }
    ASSERT_EQ(rows<D>(S), expected) << "seed " << seed;
    for (Eigen::Index i = 0; i < S.rows(); ++i) {
      std::array<int, D> row;
      for (int j = 0; j < D; ++j) row[j] = S(i, j);
      const auto c = test::brute_largest<D>(test::brute_case<D>(V, row));
      ASSERT_NEAR(C(i, 0), (*c)[0], 1e-7) << "seed " << seed << " row " << i;
      ASSERT_NEAR(C(i, 1), (*c)[1], 1e-7) << "seed " << seed << " row " << i;
    }
    // The screened lens path (floor > -1) returns exactly the rows with c'1 ≥ floor.
    for (double floor : {-0.9, -0.6, -0.3}) {
      Eigen::Matrix<int, Eigen::Dynamic, D> Sf;
      Eigen::MatrixX2d Cf;
      gamma_values(V, floor, Sf, Cf);
      Rows<D> want;
      for (Eigen::Index i = 0; i < S.rows(); ++i)
        if (C(i, 1) >= floor) want.push_back(rows<D>(S)[i]);
      ASSERT_EQ(rows<D>(Sf), want) << "seed " << seed << " floor " << floor;
    }
  }
}

TEST(GammaGraph, LargestEmptyValues2DMatchBruteForce) { expect_values_match_brute<2>(16, 20); }
TEST(GammaGraph, LargestEmptyValues3DMatchBruteForce) { expect_values_match_brute<3>(11, 5); }

template <int D>
void expect_ranges_match_brute(int n, unsigned seeds) {
  const std::vector<GammaRange> ranges{{-1, 1, 0, 1},       {-1, 1, -1, 0},       {-0.25, 0.25, -0.25, 0},
                                       {-1, 1, -1, -0.9},   {-0.3, 0.6, 0.2, 0.9}, {0.1, 1, -0.6, 0.4},
                                       {-1, -0.2, -0.7, 1}, {-1, 1, 0.5, 1}};
  for (unsigned seed = 200; seed < 200 + seeds; ++seed) {
    const auto V = random_points<D>(n, seed);
    for (const auto& g : ranges)
      ASSERT_EQ(fast<D>(V, g), test::brute_gamma_range<D>(V, g.c0, g.c1, g.c2, g.c3))
          << "seed " << seed << " range [" << g.c0 << "," << g.c1 << "],[" << g.c2 << "," << g.c3 << "]";
  }
}

TEST(GammaGraph, Ranges2DMatchBruteForce) { expect_ranges_match_brute<2>(14, 10); }
TEST(GammaGraph, Ranges3DMatchBruteForce) { expect_ranges_match_brute<3>(10, 3); }

// Lemmas 3.1 and 3.2: the fixed graph equals its range form(s).
template <int D>
void expect_lemmas_3_1_and_3_2(int n, unsigned seeds) {
  for (unsigned seed = 300; seed < 300 + seeds; ++seed) {
    const auto V = random_points<D>(n, seed);
    for (double c1 : kGrid)
      for (double c0 : kGrid) {
        if (std::abs(c0) > std::abs(c1)) continue;
        Rows<D> expected = fast<D>(V, GammaRange{c0, 1, c1, 1});
        if (c1 < 0) expected = merged<D>(expected, fast<D>(V, GammaRange{c1, 1, std::abs(c0), 1}));
        ASSERT_EQ(fast<D>(V, c0, c1), expected) << "seed " << seed << " c0 " << c0 << " c1 " << c1;
      }
  }
}

TEST(GammaGraph, Lemmas3_1And3_2In2D) { expect_lemmas_3_1_and_3_2<2>(30, 5); }
TEST(GammaGraph, Lemmas3_1And3_2In3D) { expect_lemmas_3_1_and_3_2<3>(14, 2); }

// Lemma 3.3: nested parameter intervals give nested graphs.
TEST(GammaGraph, Lemma3_3Monotonicity) {
  const std::vector<GammaRange> chain{{0.2, 0.6, 0.4, 0.8}, {0, 0.7, 0.1, 0.9}, {-0.5, 0.9, -0.3, 1}, {-1, 1, -1, 1}};
  for (unsigned seed = 0; seed < 6; ++seed) {
    const auto V = random_points<2>(40, seed);
    const auto W = random_points<3>(16, seed);
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
      EXPECT_TRUE(subset<2>(fast<2>(V, chain[i]), fast<2>(V, chain[i + 1]))) << seed << " " << i;
      EXPECT_TRUE(subset<3>(fast<3>(W, chain[i]), fast<3>(W, chain[i + 1]))) << seed << " " << i;
    }
    EXPECT_LT(fast<2>(V, chain[0]).size(), fast<2>(V, chain[3]).size());
  }
}

// §3.2: γ(1,1) empty, γ(-1,-1) complete (no three points collinear).
TEST(GammaGraph, ExtremeParametersGiveEmptyAndCompleteGraphs) {
  for (unsigned seed = 0; seed < 5; ++seed) {
    const auto V = random_points<2>(30, seed);
    const auto W = random_points<3>(15, seed);
    EXPECT_TRUE(fast<2>(V, 1, 1).empty());
    EXPECT_TRUE(fast<3>(W, 1, 1).empty());
    EXPECT_EQ(fast<2>(V, -1, -1).size(), 30u * 29 / 2);
    EXPECT_EQ(fast<3>(W, -1, -1).size(), 15u * 14 * 13 / 6);
  }
}

// γ(-1,1) = γ(1,-1) = convex hull: all other vertices on one side.
TEST(GammaGraph, MinusOneOneIsConvexHull) {
  for (unsigned seed = 0; seed < 5; ++seed) {
    const auto W = random_points<3>(25, seed);
    Rows<3> hull;
    for (const auto& row : test::all_subsets<3>(25)) {
      int pos = 0, neg = 0;
      for (int i = 0; i < 25; ++i) {
        const int s = orientation(Eigen::Vector3d(W.row(row[0])), Eigen::Vector3d(W.row(row[1])),
                                  Eigen::Vector3d(W.row(row[2])), Eigen::Vector3d(W.row(i)));
        pos += s > 0, neg += s < 0;
      }
      if (pos == 0 || neg == 0) hull.push_back(row);
    }
    EXPECT_EQ(fast<3>(W, -1, 1), hull);
    EXPECT_EQ(fast<3>(W, 1, -1), hull);
    // A closed triangulated hull of h vertices has 2h - 4 triangles.
    std::set<int> on_hull;
    for (const auto& t : hull) on_hull.insert(t.begin(), t.end());
    EXPECT_EQ(hull.size(), 2 * on_hull.size() - 4);
  }
}

TEST(GammaGraph, InvariantUnderScalingAndTranslation) {
  const std::vector<std::pair<double, double>> params{{-0.21, 0.5}, {0.17, -0.5}, {0, 0}, {-1, 1}};
  for (unsigned seed = 0; seed < 4; ++seed) {
    const auto V = random_points<2>(60, seed);
    const auto W = random_points<3>(25, seed);
    for (const auto& [c0, c1] : params) {
      const auto e = fast<2>(V, c0, c1);
      const auto t = fast<3>(W, c0, c1);
      // 2^±1000: exact copies whose squared lengths would overflow or
      // underflow (the 3D hull once had 638 triangles for 56 there).
      for (double scale : {1e-6, 1e6, 0x1p-1000, 0x1p1000}) {
        EXPECT_EQ(fast<2>(Eigen::MatrixX2d(V * scale), c0, c1), e) << scale;
        EXPECT_EQ(fast<3>(Eigen::MatrixX3d(W * scale), c0, c1), t) << scale;
      }
      EXPECT_EQ(fast<2>(Eigen::MatrixX2d(V.array() + 1e6), c0, c1), e);
      EXPECT_EQ(fast<3>(Eigen::MatrixX3d(W.array() + 1e6), c0, c1), t);
    }
  }
}

// Exactly co-circular points: 12 integer points on the circle of radius 5
// (0.6 and 0.8 would not be exact in binary).
Eigen::MatrixX2d cocircular12() {
  Eigen::MatrixX2d V(12, 2);
  V << 5, 0, 4, 3, 3, 4, 0, 5, -3, 4, -4, 3, -5, 0, -4, -3, -3, -4, 0, -5, 3, -4, 4, -3;
  return V;
}

TEST(GammaGraph, CocircularSetHasAllChordsInDelaunayRange) {
  const auto V = cocircular12();
  const GammaRange dt{-1, 1, 0, 1};
  EXPECT_EQ(fast<2>(V, dt).size(), 66u);  // every chord: crossing edges on the empty circle (§3.3)
  EXPECT_EQ(fast<2>(V, dt), test::brute_gamma_range<2>(V, -1, 1, 0, 1));
  EXPECT_EQ(fast<2>(V, -1, 1).size(), 12u);  // the polygon is the hull
  EXPECT_EQ(fast<2>(V, -1, 1), test::brute_gamma<2>(V, -1, 1));
  for (double c : {-0.5, 0.0, 0.3}) EXPECT_EQ(fast<2>(V, c, c), test::brute_gamma<2>(V, c, c)) << c;
  // With the centre added the chords through it are blocked, the rest not.
  Eigen::MatrixX2d W(13, 2);
  W << V, Eigen::RowVector2d(0, 0);
  EXPECT_EQ(fast<2>(W, dt), test::brute_gamma_range<2>(W, -1, 1, 0, 1));
  EXPECT_EQ(fast<2>(W, GammaRange{-1, 1, -1, 1}), test::brute_gamma_range<2>(W, -1, 1, -1, 1));
}

// A lattice is co-circular square by square (each square's diagonals are
// chords of an empty circle, one not a Delaunay edge), with points all
// around: its chords' profiles come from their square's points alone (not
// a scan of every point), and must equal the brute force.
TEST(GammaGraph, LatticeSquaresMatchBruteForce) {
  for (const auto& [nx, ny, hx, hy] : {std::array<double, 4>{5, 5, 1, 1}, std::array<double, 4>{4, 6, 0.5, 0.75}}) {
    Eigen::MatrixX2d V(static_cast<Eigen::Index>(nx * ny), 2);
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) V.row(static_cast<Eigen::Index>(i * ny + j)) << i * hx, j * hy;
    for (double c1 : kGrid)
      for (double c0 : kGrid)
        if (std::abs(c0) <= std::abs(c1)) {
          ASSERT_EQ(fast<2>(V, c0, c1), test::brute_gamma<2>(V, c0, c1)) << nx << " c0 " << c0 << " c1 " << c1;
        }
    for (const auto& g : {GammaRange{-1, 1, 0, 1}, GammaRange{-1, 1, -1, 1}, GammaRange{0, 0.5, 0.2, 1}})
      EXPECT_EQ(fast<2>(V, g), test::brute_gamma_range<2>(V, g.c0, g.c1, g.c2, g.c3)) << nx;
  }
}

// In space each unit cube of a lattice is co-spherical, its square faces
// co-circular: a cluster's triangles are bounded by its points and the
// apexes across its boundary (not a scan of every point).
TEST(GammaGraph, CubicLatticeMatchesBruteForce) {
  for (const auto& [n, h] : {std::array<double, 2>{3, 1}, std::array<double, 2>{3, 0.75}}) {
    Eigen::MatrixX3d V(static_cast<Eigen::Index>(n * n * (n + 1)), 3);
    Eigen::Index r = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k <= n; ++k) V.row(r++) << i, j * h, k * 0.5;
    for (double c : {-0.6, 0.0, 0.4, 1.0}) EXPECT_EQ(fast<3>(V, c, -c), test::brute_gamma<3>(V, c, -c)) << c;
    // The hull's faces are planar groups of 9 and 12 points: queries with a
    // half-space (γ(±1,1), ranges reaching c'0 = -1 and c'1 = 1) take in
    // the triangles with another point of the face in their circle, the
    // others leave them out.
    // The unit cubes are co-spherical clusters: γ(0, 0.17) and γ(-0.1, 0.17)
    // take in both diagonals of their square faces (a face's pencil is
    // empty up to t ≈ ±0.18), which only the cluster's faces list there.
    for (const auto& [c0, c1] :
         {std::array<double, 2>{-1, 1}, {1, 1}, {0.5, 1}, {-0.3, 0.9}, {0, 0.17}, {-0.1, 0.17}})
      EXPECT_EQ(fast<3>(V, c0, c1), test::brute_gamma<3>(V, c0, c1)) << c0 << " " << c1;
    for (const auto& g : {GammaRange{-1, 1, 0, 1}, GammaRange{-1, 1, -1, 1}, GammaRange{-0.5, 0.5, 0, 1},
                          GammaRange{-1, 1, 0.5, 1}, GammaRange{-0.9, 1, 0, 0.95}, GammaRange{0, 1, 0, 1},
                          GammaRange{-1, -0.5, 0, 1}})
      EXPECT_EQ(fast<3>(V, g), test::brute_gamma_range<3>(V, g.c0, g.c1, g.c2, g.c3)) << h;
  }
}

// Integer points on one sphere (x² + y² + z² = 9: 30 points) and a few
// outside it: one co-spherical cluster, whose triangles with cluster points
// on both sides of their plane are left out of the fixed queries with
// c0 ≠ -c1, c1 ≥ 0 (see gamma_graph.cpp, Listing) and listed for the others.
TEST(GammaGraph, CosphericalClusterMatchesBruteForce) {
  std::vector<Eigen::RowVector3d> rows;
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z)
        if (x * x + y * y + z * z == 9) rows.emplace_back(x, y, z);
  for (const auto& [x, y, z] : {std::array<double, 3>{4, 1, 0.5}, {-1, -4.5, 2}, {0.5, 2, -5}}) rows.emplace_back(x, y, z);
  Eigen::MatrixX3d V(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) V.row(static_cast<Eigen::Index>(i)) = rows[i];
  ASSERT_EQ(V.rows(), 33);
  for (double c1 : kGrid)
    for (double c0 : kGrid)
      if (std::abs(c0) <= std::abs(c1)) {
        EXPECT_EQ(fast<3>(V, c0, c1), test::brute_gamma<3>(V, c0, c1)) << c0 << " " << c1;
      }
  EXPECT_EQ(fast<3>(V, GammaRange{-1, 1, 0, 1}), test::brute_gamma_range<3>(V, -1, 1, 0, 1));
}

Eigen::MatrixX3d cube() {
  Eigen::MatrixX3d V(8, 3);
  for (int i = 0; i < 8; ++i) V.row(i) << (i & 1 ? 1 : -1), (i & 2 ? 1 : -1), (i & 4 ? 1 : -1);
  return V;
}

TEST(GammaGraph, CubeIsCosphericalAndCoplanarFaces) {
  const auto V = cube();
  EXPECT_EQ(fast<3>(V, GammaRange{-1, 1, 0, 1}).size(), 56u);  // every triangle on the empty sphere
  for (const auto& g : {GammaRange{-1, 1, 0, 1}, GammaRange{-1, 1, -1, 1}, GammaRange{-0.5, 0.5, 0.5, 1}})
    EXPECT_EQ(fast<3>(V, g), test::brute_gamma_range<3>(V, g.c0, g.c1, g.c2, g.c3));
  // Hull: the 4 triangles of each of the 6 square faces.
  EXPECT_EQ(fast<3>(V, -1, 1).size(), 24u);
  for (double c : {-0.6, 0.0, 0.4}) EXPECT_EQ(fast<3>(V, c, c), test::brute_gamma<3>(V, c, c)) << c;
  // Cube plus its centre: the centre lies in the planes of the diagonal rectangles.
  Eigen::MatrixX3d W(9, 3);
  W << V, Eigen::RowVector3d(0, 0, 0);
  EXPECT_EQ(fast<3>(W, GammaRange{-1, 1, -1, 1}), test::brute_gamma_range<3>(W, -1, 1, -1, 1));
  EXPECT_EQ(fast<3>(W, 0.2, -0.4), test::brute_gamma<3>(W, 0.2, -0.4));
}

TEST(GammaGraph, DuplicatesAreMergedToFirstOccurrence) {
  const auto V = random_points<2>(20, 7);
  Eigen::MatrixX2d W(23, 2);
  W << V, V.row(3), V.row(0), V.row(3);
  for (const auto& [c0, c1] : std::vector<std::pair<double, double>>{{0, 0}, {-0.2, 0.5}, {0.1, -0.6}}) {
    EXPECT_EQ(fast<2>(W, c0, c1), fast<2>(V, c0, c1));
  }
  const auto T = random_points<3>(12, 7);
  Eigen::MatrixX3d U(13, 3);
  U << T.row(5), T;  // duplicate first: the copy at row 6 is the one left out
  const auto g = fast<3>(U, -0.3, 0.4);
  for (const auto& t : g) EXPECT_TRUE(std::find(t.begin(), t.end(), 6) == t.end());
  EXPECT_FALSE(g.empty());
}

TEST(GammaGraph, CollinearAndCoplanarInput) {
  Eigen::MatrixX2d L(5, 2);
  L << 0, 0, 3, 3, 1, 1, 4, 4, 2, 2;
  // Only consecutive points: every other pair has a vertex in its open segment.
  const Rows<2> chain{{{0, 2}}, {{1, 3}}, {{1, 4}}, {{2, 4}}};
  EXPECT_EQ(fast<2>(L, -1, -1), chain);
  EXPECT_EQ(fast<2>(L, 1, 1), chain);  // no vertex off the line: both half-planes empty
  EXPECT_EQ(fast<2>(L, GammaRange{-1, 1, 0, 1}), chain);
  EXPECT_EQ(fast<2>(L, GammaRange{-1, 1, -1, 1}), test::brute_gamma_range<2>(L, -1, 1, -1, 1));
  // More of them, shuffled and unevenly spaced, on a slanted line (exact:
  // y = x/2 in binary fractions): the fast graph (which tells collinear
  // input before any triangulation) against the brute force.
  std::vector<int> steps(24);
  std::iota(steps.begin(), steps.end(), -12);
  std::shuffle(steps.begin(), steps.end(), std::mt19937(11));
  Eigen::MatrixX2d M(24, 2);
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    const int k = steps[static_cast<std::size_t>(i)];
    const double x = k + k * k / 64.0;  // increasing in k: distinct
    M.row(i) << x, x / 2;
  }
  for (const double c : {-1.0, -0.5, 0.0, 0.7, 1.0}) EXPECT_EQ(fast<2>(M, c, -c), test::brute_gamma<2>(M, c, -c)) << c;
  EXPECT_EQ(fast<2>(M, GammaRange{-1, 1, 0, 1}), test::brute_gamma_range<2>(M, -1, 1, 0, 1));
  Eigen::MatrixX3d C(4, 3);
  C << 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3;
  EXPECT_TRUE(fast<3>(C, -1, -1).empty());  // collinear: no triangles at all
  Eigen::MatrixX3d P(5, 3);
  P << 0, 0, 0, 2, 0, 0, 0, 2, 0, 2, 2, 0, 1, 0.5, 0;  // coplanar, one inside
  for (const auto& g : {GammaRange{-1, 1, -1, 1}, GammaRange{-1, 1, 0, 1}, GammaRange{0.5, 1, 0.5, 1}})
    EXPECT_EQ(fast<3>(P, g), test::brute_gamma_range<3>(P, g.c0, g.c1, g.c2, g.c3));
  for (double c : {-1.0, -0.4, 0.0, 1.0}) EXPECT_EQ(fast<3>(P, c, c), test::brute_gamma<3>(P, c, c)) << c;
  // A 3D set with a coplanar 4-tuple off the hull plane: degenerate disc vertices.
  Eigen::MatrixX3d Q(6, 3);
  Q << 0, 0, 0, 4, 0, 0, 0, 4, 0, 1, 1, 0, 1, 1, 3, 2, 1, -2;
  for (const auto& g : {GammaRange{-1, 1, -1, 1}, GammaRange{-1, 1, 0, 1}, GammaRange{-1, 1, -1, -0.5}})
    EXPECT_EQ(fast<3>(Q, g), test::brute_gamma_range<3>(Q, g.c0, g.c1, g.c2, g.c3));
  for (double c : {-1.0, -0.4, 0.0, 1.0}) EXPECT_EQ(fast<3>(Q, c, -c), test::brute_gamma<3>(Q, c, -c)) << c;
}

TEST(GammaGraph, TooFewPointsGiveTrivialGraphs) {
  EXPECT_TRUE(fast<2>(Eigen::MatrixX2d(0, 2), 0, 0).empty());
  EXPECT_TRUE(fast<2>(Eigen::MatrixX2d::Ones(1, 2), 0, 0).empty());
  Eigen::MatrixX2d two(2, 2);
  two << 0, 0, 1, 0;
  EXPECT_EQ(fast<2>(two, 1, 1).size(), 1u);  // no other vertex: every N_γ is empty
  Eigen::MatrixX3d three(3, 3);
  three << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  EXPECT_TRUE(fast<3>(Eigen::MatrixX3d(three.topRows(2)), -1, -1).empty());
  EXPECT_EQ(fast<3>(three, 1, 1).size(), 1u);
}

TEST(GammaGraph, RejectsImpossibleRequests) {
  const auto V = random_points<2>(5, 1);
  test::expect_error<InvalidInput>([&] { gamma_graph(V, 0.5, 0.2); }, {"|c0| ≤ |c1|"});
  test::expect_error<InvalidInput>([&] { gamma_graph(V, 0, 1.5); }, {"c1", "outside [-1, 1]"});
  test::expect_error<InvalidInput>([&] { gamma_graph(V, GammaRange{0.5, 0.2, 0, 1}); }, {"empty parameter interval"});
  Eigen::MatrixX2d bad = V;
  bad(2, 1) = std::nan("");
  test::expect_error<InvalidInput>([&] { gamma_graph(bad, 0, 0); }, {"non-finite"});
}

}  // namespace
}  // namespace scanstation
