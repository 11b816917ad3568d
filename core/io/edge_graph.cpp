#include "core/io/edge_graph.h"

#include "core/io/number_text.h"

namespace scanstation::io {

namespace {

void append_points(std::string& out, const Eigen::MatrixX3d& V, const char* prefix) {
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    out += prefix;
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ' ';
      append_double(out, V(i, k));
    }
    out += '\n';
  }
}

void append_edges(std::string& out, const Eigen::MatrixX2i& E, const char* prefix, int base) {
  for (Eigen::Index e = 0; e < E.rows(); ++e) {
    out += prefix;
    append_int(out, E(e, 0) + base);
    out += ' ';
    append_int(out, E(e, 1) + base);
    out += '\n';
  }
}

}  // namespace

std::string write_edges_obj(const Eigen::MatrixX3d& V, const Eigen::MatrixX2i& E) {
  std::string out = "# scanstation geometric graph: " + std::to_string(V.rows()) + " points, " +
                    std::to_string(E.rows()) + " edges\n";
  append_points(out, V, "v ");
  append_edges(out, E, "l ", 1);
  return out;
}

std::string write_edges_ply(const Eigen::MatrixX3d& V, const Eigen::MatrixX2i& E) {
  std::string out = "ply\nformat ascii 1.0\ncomment scanstation geometric graph\nelement vertex " +
                    std::to_string(V.rows()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement edge " +
                    std::to_string(E.rows()) + "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  append_points(out, V, "");
  append_edges(out, E, "", 0);
  return out;
}

}  // namespace scanstation::io
