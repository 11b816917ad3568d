#include "smoothing/mesh_edges.h"

#include "core/errors.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace scanstation {

namespace {

struct HalfEdge {
  std::uint64_t key;  // (min, max) vertex pair
  int face;
  int edge;
  bool forward;       // runs from the smaller to the larger index
};

std::string edge_name(const Eigen::MatrixX3i& F, const HalfEdge& h) {
  return "edge (" + std::to_string(F(h.face, h.edge)) + ", " + std::to_string(F(h.face, (h.edge + 1) % 3)) +
         ") of face " + std::to_string(h.face);
}

// Every edge can have two faces while a vertex joins two surfaces (two
// tetrahedra sharing a corner): its faces then form several fans, and the
// patches around it no disc. Walks one fan per vertex across the edges
// leaving it and compares its length with the vertex's face count.
void require_one_fan_per_vertex(const Eigen::MatrixX3i& F, const MeshEdges& edges) {
  const Eigen::Index vertex_count = F.size() > 0 ? F.maxCoeff() + 1 : 0;
  std::vector<int> faces_at(static_cast<std::size_t>(vertex_count), 0), fan_of(static_cast<std::size_t>(vertex_count), -1);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      ++faces_at[static_cast<std::size_t>(F(f, k))];
      if (fan_of[static_cast<std::size_t>(F(f, k))] < 0) fan_of[static_cast<std::size_t>(F(f, k))] = 3 * f + k;
    }
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    const int start = fan_of[static_cast<std::size_t>(v)];
    if (start < 0) continue;
    int f = start / 3, k = start % 3, length = 0;
    do {  // edge k of face f leaves v; v is corner (e + 1) % 3 of the face across it
      const int e = edges.neighbour_edge(f, k);
      f = edges.neighbour(f, k);
      k = (e + 1) % 3;
      ++length;
    } while (3 * f + k != start && length <= faces_at[static_cast<std::size_t>(v)]);
    if (length != faces_at[static_cast<std::size_t>(v)])
      throw TopologyError("vertex " + std::to_string(v) + ": its " + std::to_string(faces_at[static_cast<std::size_t>(v)]) +
                          " faces form more than one fan (the surface pinches there): smoothing needs a closed "
                          "manifold surface");
  }
}

}  // namespace

MeshEdges mesh_edges(const Eigen::MatrixX3i& F) {
  std::vector<HalfEdge> halves;
  halves.reserve(3 * F.rows());
  for (int f = 0; f < F.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = F(f, e), b = F(f, (e + 1) % 3);
      const std::uint64_t lo = std::min(a, b), hi = std::max(a, b);
      halves.push_back({lo << 32 | hi, f, e, a < b});
    }
  std::sort(halves.begin(), halves.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.key != y.key ? x.key < y.key : x.forward > y.forward;
  });
  MeshEdges edges{Eigen::MatrixX3i(F.rows(), 3), Eigen::MatrixX3i(F.rows(), 3)};
  for (std::size_t i = 0; i < halves.size(); i += 2) {
    const HalfEdge& h = halves[i];
    const bool paired = i + 1 < halves.size() && halves[i + 1].key == h.key;
    if (!paired || (i + 2 < halves.size() && halves[i + 2].key == h.key))
      throw TopologyError(edge_name(F, h) + " is not shared by exactly two faces: smoothing needs a closed manifold "
                          "surface");
    const HalfEdge& g = halves[i + 1];
    if (h.forward == g.forward)
      throw TopologyError(edge_name(F, h) + " runs the same way in both its faces: the surface is not consistently "
                          "oriented");
    edges.neighbour(h.face, h.edge) = g.face;
    edges.neighbour_edge(h.face, h.edge) = g.edge;
    edges.neighbour(g.face, g.edge) = h.face;
    edges.neighbour_edge(g.face, g.edge) = h.edge;
  }
  require_one_fan_per_vertex(F, edges);
  return edges;
}

}  // namespace scanstation
