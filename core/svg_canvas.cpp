#include "core/svg_canvas.h"

#include "core/io/number_text.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace scanstation {

namespace {
void append_xy(std::string& out, double x, double y) {
  io::append_double(out, x);
  out += ',';
  io::append_double(out, y);
}

std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}
}  // namespace

SvgCanvas::SvgCanvas(const Eigen::AlignedBox2d& bounds, double width_px) : width_px_(width_px) {
  Eigen::AlignedBox2d box = bounds;
  if (box.isEmpty()) box = Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  double extent = box.sizes().maxCoeff();
  if (!(extent > 0.0)) extent = std::max(1.0, box.max().cwiseAbs().maxCoeff());
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(0.05 * extent);
  view_ = Eigen::AlignedBox2d(box.min() - margin, box.max() + margin);
  // Degenerate (collinear) data still gets a visible band.
  for (int a = 0; a < 2; ++a)
    if (view_.sizes()[a] < 0.1 * extent) {
      view_.min()[a] -= 0.05 * extent;
      view_.max()[a] += 0.05 * extent;
    }
  data_per_px_ = view_.sizes().x() / width_px_;
}

void SvgCanvas::polygon(const Eigen::MatrixX2d& V, const SvgStyle& style) {
  body_ += "  <polygon fill=\"" + style.fill + "\" stroke=\"" + style.stroke + "\" stroke-width=\"";
  io::append_double(body_, px_to_data(style.stroke_px));
  body_ += "\" stroke-linejoin=\"round\" points=\"";
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    if (i > 0) body_ += ' ';
    append_xy(body_, V(i, 0), V(i, 1));
  }
  body_ += "\"/>\n";
}

void SvgCanvas::segments(const Eigen::MatrixX2d& V, const Eigen::MatrixX2i& E, const SvgStyle& style) {
  body_ += "  <path fill=\"none\" stroke=\"" + style.stroke + "\" stroke-width=\"";
  io::append_double(body_, px_to_data(style.stroke_px));
  body_ += "\" stroke-linecap=\"round\"";
  if (!style.dash.empty()) {
    // The pattern is given in screen pixels, drawn in data units.
    body_ += " stroke-dasharray=\"";
    std::istringstream pattern(style.dash);
    double px = 0.0;
    for (bool first = true; pattern >> px; first = false) {
      if (!first) body_ += ' ';
      io::append_double(body_, px_to_data(px));
    }
    body_ += "\"";
  }
  body_ += " d=\"";
  for (Eigen::Index e = 0; e < E.rows(); ++e) {
    body_ += e > 0 ? " M" : "M";
    append_xy(body_, V(E(e, 0), 0), V(E(e, 0), 1));
    body_ += " L";
    append_xy(body_, V(E(e, 1), 0), V(E(e, 1), 1));
  }
  body_ += "\"/>\n";
}

void SvgCanvas::points(const Eigen::MatrixX2d& P, const SvgStyle& style) {
  body_ += "  <g fill=\"" + style.fill + "\" stroke=\"none\">\n";
  std::string radius;
  io::append_double(radius, px_to_data(style.point_px));
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    body_ += "    <circle cx=\"";
    io::append_double(body_, P(i, 0));
    body_ += "\" cy=\"";
    io::append_double(body_, P(i, 1));
    body_ += "\" r=\"" + radius + "\"/>\n";
  }
  body_ += "  </g>\n";
}

void SvgCanvas::caption(const std::string& text) {
  overlay_ += "  <text x=\"8\" y=\"18\" font-family=\"sans-serif\" font-size=\"13\">" + escape(text) + "</text>\n";
}

std::string SvgCanvas::str() const {
  const double height_px = width_px_ * view_.sizes().y() / view_.sizes().x();
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"";
  io::append_double(out, width_px_);
  out += "\" height=\"";
  io::append_double(out, std::round(height_px));
  out += "\" viewBox=\"0 0 ";
  io::append_double(out, width_px_);
  out += ' ';
  io::append_double(out, std::round(height_px));
  out += "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // Data units to screen pixels with y up: translate the view's top-left to
  // the origin, scale, flip y.
  const double s = 1.0 / data_per_px_;
  out += "<g data-scanstation=\"view\" transform=\"matrix(";
  io::append_double(out, s);
  out += " 0 0 ";
  io::append_double(out, -s);
  out += ' ';
  io::append_double(out, -view_.min().x() * s);
  out += ' ';
  io::append_double(out, view_.max().y() * s);
  out += ")\">\n" + body_ + "</g>\n" + overlay_ + "</svg>\n";
  return out;
}

}  // namespace scanstation
