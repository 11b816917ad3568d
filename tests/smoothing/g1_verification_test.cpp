#include "smoothing/g1_verification.h"

#include <gtest/gtest.h>

#include <cmath>

namespace scanstation {
namespace {

// A flat cubic patch: the control point of exponents (i, j, k) at the
// barycentric point (i, j, k)/3 of the triangle (a, b, c).
CubicTriangle flat_patch(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  CubicTriangle patch;
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; i + j <= 3; ++j) {
      const int k = 3 - i - j;
      patch[control_index(i, j, k)] = (i * a + j * b + k * c) / 3.0;
    }
  return patch;
}

// Two patches in the plane z = 0 across the edge A–B. Q's cross-edge
// derivative is bent so that its y component, −((s − m)² − w²) in Q's
// parameter s, turns positive in a band of width 2w about m: there Q folds
// back over P, its normal −z against P's +z, while both tangent planes stay
// z = 0 (no residual anywhere).
BezierSurface folded_pair(double m, double w) {
  const Eigen::Vector3d A(0, 0, 0), B(1, 0, 0), C(0.5, 1, 0), D(0.5, -1, 0);
  BezierSurface surface;
  surface.patches.push_back(flat_patch(A, B, C));
  CubicTriangle Q = flat_patch(B, A, D);  // its edge 0 runs B → A
  const double b[3] = {m * m - w * w, m * m - w * w - m, (1 - m) * (1 - m) - w * w};  // Bernstein of (s − m)² − w²
  for (int i = 0; i < 3; ++i)
    Q[control_index(2 - i, i, 1)] = Q[control_index(3 - i, i, 0)] + Eigen::Vector3d(0, -b[i], 0);
  surface.patches.push_back(Q);
  surface.macro = {0, 1};
  return surface;
}

TEST(VerifyG1, FindsAFoldNarrowerThanItsSamples) {
  // The band (0.55, 0.59) of Q lies between the samples at 0.5 and 0.625.
  const BezierSurface narrow = folded_pair(0.57, 0.02);
  const G1Verification g1 = verify_g1(narrow, 7);
  EXPECT_EQ(g1.shared_edges, 1u);
  EXPECT_EQ(g1.folded_edges, 1u);
  EXPECT_EQ(g1.max_normal_angle, M_PI);
  EXPECT_LT(g1.max_residual, 1e-12);
  // Without the band (w² < 0: y stays negative) the pair is G¹.
  const G1Verification flat = verify_g1(folded_pair(0.57, 0.0), 7);
  EXPECT_EQ(flat.folded_edges, 0u);
  EXPECT_LT(flat.max_normal_angle, 1e-12);
}

TEST(VerifyG1, AFoldTheWholeEdgeLongAndOneTouchingZero) {
  // Q's derivative positive along all of the edge: folded everywhere.
  const G1Verification whole = verify_g1(folded_pair(0.5, 2.0), 7);
  EXPECT_EQ(whole.folded_edges, 1u);
  EXPECT_EQ(whole.max_normal_angle, M_PI);
  // (s − ½)² touching zero at s = ½: Q's normal vanishes there, a singular
  // point and no tangent plane — not G¹ either. Rounding decides whether g
  // meets 0 there, but the sample at ½ does.
  const G1Verification touching = verify_g1(folded_pair(0.5, 0.0), 7);
  EXPECT_EQ(touching.max_normal_angle, M_PI);
}

}  // namespace
}  // namespace scanstation
