#include "core/svg_canvas.h"

#include "core/io/number_text.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>
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
  // Sizes are taken by halves: data near the largest doubles (±1e308) has
  // sides that overflow, and the view came out infinite.
  double half = (box.max() / 2 - box.min() / 2).maxCoeff();
  if (!(half > 0.0)) half = std::max(0.5, box.max().cwiseAbs().maxCoeff() / 2);
  const double largest = std::numeric_limits<double>::max();
  const auto widened = [&](double lo, double hi, double by) {
    return std::pair(std::max(lo - by, -largest), std::min(hi + by, largest));
  };
  for (int a = 0; a < 2; ++a) {
    // A margin of a twentieth of the extent; degenerate (collinear) data
    // still gets a visible band.
    auto [lo, hi] = widened(box.min()[a], box.max()[a], 0.1 * half);
    if (hi / 2 - lo / 2 < 0.1 * half) std::tie(lo, hi) = widened(lo, hi, 0.1 * half);
    view_.min()[a] = lo;
    view_.max()[a] = hi;
  }
  data_per_px_ = (half_size(0) / width_px_) * 2;
}

double SvgCanvas::half_size(int axis) const { return view_.max()[axis] / 2 - view_.min()[axis] / 2; }

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
  const double height_px = width_px_ * (half_size(1) / half_size(0));
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
