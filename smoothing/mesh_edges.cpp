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
  return edges;
}

}  // namespace scanstation
