#include "reconstruct/boundary_svg.h"

#include "core/bounding_box.h"
#include "core/io/number_text.h"
#include "core/svg_canvas.h"
#include "reconstruct/gamma_graph.h"

#include <algorithm>
#include <array>
#include <vector>

namespace scanstation {

namespace {
// Distinct undirected edges of a set of triangles.
template <typename Triangles>
Eigen::MatrixX2i edges_of(const Triangles& T) {
  std::vector<std::array<int, 2>> e;
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 3; ++k) e.push_back({std::min(T(t, k), T(t, (k + 1) % 3)), std::max(T(t, k), T(t, (k + 1) % 3))});
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  Eigen::MatrixX2i out(static_cast<Eigen::Index>(e.size()), 2);
  for (std::size_t i = 0; i < e.size(); ++i) out.row(static_cast<Eigen::Index>(i)) << e[i][0], e[i][1];
  return out;
}
}  // namespace

std::string boundary_svg(const CurveReconstruction& r) {
  SvgCanvas canvas(bounding_box(r.points));
  // After augmentation (§5.4, Figure 5.7) the graph constricted was
  // γ([-1,1],[c0,1]): its extra edges beyond the Delaunay ones, thin.
  if (r.statistics.c0_used) {
    GammaRange range;
    range.c2 = *r.statistics.c0_used;
    canvas.segments(r.points, gamma_graph(r.points, range), SvgStyle{"#d0b0d0", "none", 0.5, 0.0, "2 3"});
  }
  canvas.segments(r.points, edges_of(r.delaunay), SvgStyle{"#b0b0b0", "none", 0.8, 0.0, "4 3"});
  canvas.segments(r.points, edges_of(r.interior), SvgStyle{"#7f9cc7", "none", 0.8, 0.0, ""});
  canvas.polygon(r.polygon.vertices, SvgStyle{"#1f4e9c", "#dce6f580", 2.2, 0.0, ""});
  Eigen::MatrixX2d inside(static_cast<Eigen::Index>(r.statistics.interior_vertices.size()), 2);
  for (std::size_t k = 0; k < r.statistics.interior_vertices.size(); ++k)
    inside.row(static_cast<Eigen::Index>(k)) = r.points.row(r.statistics.interior_vertices[k]);
  canvas.points(r.polygon.vertices, SvgStyle{"none", "#c0392b", 0.0, 2.5, ""});
  canvas.points(inside, SvgStyle{"none", "black", 0.0, 3.0, ""});
  std::string caption = std::to_string(r.points.rows()) + " points, " + std::to_string(r.polygon.size()) +
                        " on the boundary; dashed: removed Delaunay edges";
  if (r.statistics.c0_used) {
    caption += "; dotted: γ([-1,1],[c0,1]), c0 = ";
    io::append_double(caption, *r.statistics.c0_used);
  }
  canvas.caption(caption);
  return canvas.str();
}

}  // namespace scanstation
