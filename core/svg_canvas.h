// A small SVG drawing surface for 2D results (polygons, graphs, points) with
// the y axis pointing up, as in the thesis' figures.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

namespace scanstation {

/// Style of one layer; colours are SVG colour strings.
struct SvgStyle {
  std::string stroke = "black";
  std::string fill = "none";
  double stroke_px = 1.5;  ///< line width in screen pixels, independent of the data's scale
  double point_px = 2.5;   ///< dot radius in screen pixels
  std::string dash;        ///< SVG dash pattern in screen pixels ("4 3"), empty for solid
};

/// Coordinates are written exactly (shortest round-trip decimals) in data
/// units; the y flip and scaling are a transform, so a reader gets the data
/// back bit for bit.
class SvgCanvas {
 public:
  /// bounds  the data region to show (a margin is added); width_px  image width
  SvgCanvas(const Eigen::AlignedBox2d& bounds, double width_px = 800.0);

  /// V #V by 2 vertices, drawn as a closed polygon.
  void polygon(const Eigen::MatrixX2d& V, const SvgStyle& style);
  /// V #V by 2, E #E by 2 vertex index pairs, drawn as segments.
  void segments(const Eigen::MatrixX2d& V, const Eigen::MatrixX2i& E, const SvgStyle& style);
  /// P #P by 2, drawn as dots of style.point_px radius filled with style.fill.
  void points(const Eigen::MatrixX2d& P, const SvgStyle& style);
  /// A free text caption in screen space at the top left.
  void caption(const std::string& text);

  /// The finished document.
  std::string str() const;

 private:
  double px_to_data(double px) const { return px * data_per_px_; }
  double half_size(int axis) const;  ///< half the view's side, computed without overflow
  Eigen::AlignedBox2d view_;
  double width_px_;
  double data_per_px_;
  std::string body_;
  std::string overlay_;
};

}  // namespace scanstation
