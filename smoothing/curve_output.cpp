#include "smoothing/curve_output.h"

#include "core/svg_canvas.h"

namespace scanstation {

namespace {

constexpr int samples_per_segment = 32;

SvgStyle style(std::string stroke, std::string fill, double stroke_px, double point_px, std::string dash = "") {
  SvgStyle s;
  s.stroke = std::move(stroke);
  s.fill = std::move(fill);
  s.stroke_px = stroke_px;
  s.point_px = point_px;
  s.dash = std::move(dash);
  return s;
}

Eigen::MatrixX2d sampled_curve(const G1Curve& curve) {
  const Eigen::Index n = curve.segment_count();
  Eigen::MatrixX2d points(n * samples_per_segment, 2);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int s = 0; s < samples_per_segment; ++s)
      points.row(i * samples_per_segment + s) = curve_point(curve, i, double(s) / samples_per_segment);
  return points;
}

}  // namespace

std::string g1_curve_svg(const Polygon2& polygon, const G1Curve& curve) {
  const Eigen::MatrixX2d samples = sampled_curve(curve);
  Eigen::AlignedBox2d bounds;
  for (Eigen::Index i = 0; i < curve.controls.rows(); ++i) bounds.extend(Eigen::Vector2d(curve.controls.row(i)));
  for (Eigen::Index i = 0; i < samples.rows(); ++i) bounds.extend(Eigen::Vector2d(samples.row(i)));
  SvgCanvas canvas(bounds);
  canvas.polygon(polygon.vertices, style("#999999", "none", 1.0, 0.0));
  canvas.polygon(curve.controls, style("#3366cc", "none", 0.8, 0.0, "4 3"));
  canvas.points(curve.controls, style("none", "#3366cc", 0.0, 2.0));
  canvas.polygon(samples, style("#cc2222", "none", 1.8, 0.0));
  canvas.points(polygon.vertices, style("none", "black", 0.0, 3.0));
  canvas.caption("G1 cubic Bezier curve (thesis 9.2): polygon grey, control polygon blue, curve red; " +
                 std::to_string(curve.repaired_vertices.size()) + " cusp(s) repaired");
  return canvas.str();
}

nlohmann::json g1_curve_json(const G1Curve& curve) {
  nlohmann::json segments = nlohmann::json::array();
  for (Eigen::Index i = 0; i < curve.segment_count(); ++i) {
    nlohmann::json points = nlohmann::json::array();
    for (int j = 0; j < 4; ++j) {
      const Eigen::Vector2d p = curve.control(i, j);
      points.push_back({p.x(), p.y()});
    }
    segments.push_back({{"control_points", points}});
  }
  return {{"degree", 3},
          {"closed", true},
          {"segments", segments},
          {"repaired_vertices", curve.repaired_vertices},
          {"unrepaired_vertices", curve.unrepaired_vertices}};
}

}  // namespace scanstation
