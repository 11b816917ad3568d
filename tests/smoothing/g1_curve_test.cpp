#include "smoothing/curve_output.h"
#include "smoothing/g1_curve.h"
#include "smoothing/polygon_tangents.h"

#include "core/errors.h"
#include "sim/random.h"
#include "test_support.h"

#include <cmath>
#include <numbers>

namespace scanstation {
namespace {

Polygon2 star(int points, std::uint64_t seed) {
  sim::Random random(seed);
  Polygon2 polygon;
  polygon.vertices.resize(points, 2);
  for (int i = 0; i < points; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / points;
    const double radius = 1.0 + 0.6 * random.uniform();
    polygon.vertices.row(i) << radius * std::cos(angle), radius * std::sin(angle);
  }
  return polygon;
}

TEST(PolygonTangents, UnitAndAlongTheBoundaryForEveryWeighting) {
  const Polygon2 polygon = star(40, 1);
  for (const auto weighting : {TangentWeighting::length, TangentWeighting::uniform, TangentWeighting::inverse_length}) {
    const Eigen::MatrixX2d T = polygon_tangents(polygon, weighting);
    for (Eigen::Index i = 0; i < T.rows(); ++i) {
      EXPECT_NEAR(T.row(i).norm(), 1.0, 1e-15);
      const Eigen::Vector2d chord = polygon.vertices.row((i + 1) % 40) - polygon.vertices.row((i + 39) % 40);
      EXPECT_GT(T.row(i).dot(chord), 0.0);
    }
  }
}

TEST(PolygonTangents, WeightingsDifferAsDescribed) {
  // v_{i-1} close, v_{i+1} far: inverse length leans towards the short edge.
  Polygon2 polygon;
  polygon.vertices.resize(3, 2);
  polygon.vertices << 0, 0, 0.1, 0.1, 3, 0.1;
  const Eigen::Vector2d length = polygon_tangents(polygon, TangentWeighting::length).row(1);
  const Eigen::Vector2d inverse = polygon_tangents(polygon, TangentWeighting::inverse_length).row(1);
  EXPECT_NEAR(length.x(), 3.0 / std::hypot(3.0, 0.1), 1e-14);  // v2 − v0 normalised
  EXPECT_GT(inverse.y(), length.y());
}

TEST(PolygonTangents, RepeatedVertexIsNamed) {
  Polygon2 polygon;
  polygon.vertices.resize(4, 2);
  polygon.vertices << 0, 0, 1, 0, 1, 0, 0, 1;
  test::expect_error<InvalidInput>([&] { polygon_tangents(polygon); }, {"vertex 1", "repeats"});
}

TEST(G1Curve, InterpolatesEveryVertexAndIsG1Everywhere) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Polygon2 polygon = star(5 + int(seed) * 3, seed);
    const G1Curve curve = g1_curve(polygon, polygon_tangents(polygon));
    ASSERT_EQ(curve.segment_count(), polygon.size());
    for (Eigen::Index i = 0; i < polygon.size(); ++i) {
      EXPECT_EQ(curve_point(curve, i, 0.0), Eigen::Vector2d(polygon.vertices.row(i)));
      EXPECT_NEAR((curve_point(curve, i, 1.0) - Eigen::Vector2d(polygon.vertices.row((i + 1) % polygon.size()))).norm(),
                  0.0, 1e-15);
    }
    EXPECT_TRUE(curve.unrepaired_vertices.empty());
    EXPECT_LT(max_tangent_angle(curve), 1e-12) << "seed " << seed;
  }
}

// Scaled by a power of two, the curve is the ordinary one scaled: near
// 1e±160 the squared edge lengths left the double range, every vertex
// looked repeated (underflow) or every tangent NaN (overflow).
TEST(G1Curve, ScaledByAPowerOfTwoTheCurveScalesExactly) {
  const Polygon2 polygon = star(30, 7);
  for (const auto weighting : {TangentWeighting::length, TangentWeighting::uniform, TangentWeighting::inverse_length}) {
    const Eigen::MatrixX2d tangents = polygon_tangents(polygon, weighting);
    const G1Curve curve = g1_curve(polygon, tangents);
    for (const int k : {-900, -540, 540, 1000}) {  // at 2^-1000 coordinates near 0 would be subnormal: inexact
      Polygon2 scaled = polygon;
      scaled.vertices *= std::ldexp(1.0, k);
      EXPECT_EQ(polygon_tangents(scaled, weighting), tangents) << k;
      const G1Curve again = g1_curve(scaled, tangents);
      EXPECT_EQ(Eigen::MatrixX2d(again.controls * std::ldexp(1.0, -k)), curve.controls) << k;
      EXPECT_EQ(max_tangent_angle(again), max_tangent_angle(curve)) << k;
    }
  }
}

TEST(G1Curve, CuspsFromBadTangentsAreRepaired) {
  // At v1 the far v0 dominates the length-weighted tangent v2 − v0, which
  // then points away from the near v2: p3* and q0* on the same side.
  Polygon2 polygon;
  polygon.vertices.resize(4, 2);
  polygon.vertices << 10, -1, 0, 0, 1, 1, 10, 2;
  const Eigen::MatrixX2d tangents = polygon_tangents(polygon, TangentWeighting::length);
  const G1Curve curve = g1_curve(polygon, tangents);
  EXPECT_FALSE(curve.repaired_vertices.empty());
  EXPECT_TRUE(curve.unrepaired_vertices.empty());
  EXPECT_LT(max_tangent_angle(curve), 1e-12);
  // Without the repair the same tangents give a cusp (angle π).
  G1Curve unrepaired = curve;
  const Eigen::Index tip = curve.repaired_vertices.front();
  unrepaired.controls.row(3 * tip + 1) =
      polygon.vertices.row(tip) +
      tangents.row(tip) * tangents.row(tip).dot(polygon.vertices.row((tip + 1) % 4) - polygon.vertices.row(tip)) / 3.0;
  EXPECT_GT(max_tangent_angle(unrepaired), 1.0);
}

TEST(G1Curve, SvgAndJsonHoldEveryControlPoint) {
  const Polygon2 polygon = star(12, 3);
  const G1Curve curve = g1_curve(polygon, polygon_tangents(polygon));
  const nlohmann::json json = g1_curve_json(curve);
  ASSERT_EQ(json["segments"].size(), 12u);
  EXPECT_EQ(json["degree"], 3);
  EXPECT_EQ(json["segments"][4]["control_points"][0][0].get<double>(), polygon.vertices(4, 0));
  EXPECT_EQ(json["segments"][4]["control_points"][3][1].get<double>(), polygon.vertices(5, 1));
  const std::string svg = g1_curve_svg(polygon, curve);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("cusp"), std::string::npos);
}

}  // namespace
}  // namespace scanstation
