#include "core/mesh_topology.h"

#include "core/errors.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

namespace scanstation {

namespace {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  bool unite(std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent_[a] = b;
    return true;
  }

 private:
  std::vector<std::size_t> parent_;
};

// One side of an undirected edge as seen from a face.
struct HalfEdge {
  int lo, hi;     // sorted endpoints
  int face;
  bool forward;   // the face traverses lo -> hi
  bool operator<(const HalfEdge& o) const { return std::tie(lo, hi, face) < std::tie(o.lo, o.hi, o.face); }
};

std::vector<HalfEdge> half_edges(const Eigen::MatrixX3i& F) {
  std::vector<HalfEdge> h;
  h.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b) h.push_back({std::min(a, b), std::max(a, b), f, a < b});
    }
  std::sort(h.begin(), h.end());
  return h;
}

// Faces around each vertex must form a single fan (edge-connected through
// edges at that vertex), else the vertex is non-manifold.
std::size_t count_non_manifold_vertices(const Eigen::MatrixX3i& F) {
  std::vector<std::array<int, 3>> corners;  // (vertex, face, other vertex) for both edges at the corner
  corners.reserve(static_cast<std::size_t>(F.rows()) * 6);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      corners.push_back({F(f, k), f, F(f, (k + 1) % 3)});
      corners.push_back({F(f, k), f, F(f, (k + 2) % 3)});
    }
  std::sort(corners.begin(), corners.end());
  std::size_t count = 0;
  std::vector<int> faces;
  for (std::size_t begin = 0; begin < corners.size();) {
    std::size_t end = begin;
    while (end < corners.size() && corners[end][0] == corners[begin][0]) ++end;
    faces.clear();
    for (std::size_t i = begin; i < end; ++i) faces.push_back(corners[i][1]);
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    UnionFind fans(faces.size());
    std::size_t groups = faces.size();
    auto local = [&](int f) { return static_cast<std::size_t>(std::lower_bound(faces.begin(), faces.end(), f) - faces.begin()); };
    // Corners sharing the "other vertex" share an edge at this vertex.
    std::vector<std::array<int, 2>> by_other;
    for (std::size_t i = begin; i < end; ++i) by_other.push_back({corners[i][2], corners[i][1]});
    std::sort(by_other.begin(), by_other.end());
    for (std::size_t i = 1; i < by_other.size(); ++i)
      if (by_other[i][0] == by_other[i - 1][0] && fans.unite(local(by_other[i][1]), local(by_other[i - 1][1])))
        --groups;
    if (groups > 1) ++count;
    begin = end;
  }
  return count;
}

// Propagates face orientations across manifold edges; false on a conflict
// (a Möbius-like, non-orientable surface).
bool orientable(const std::vector<HalfEdge>& h, std::size_t face_count) {
  std::vector<std::vector<std::pair<int, bool>>> neighbours(face_count);  // (face, must flip relative)
  for (std::size_t i = 0; i + 1 < h.size(); ++i)
    if (h[i].lo == h[i + 1].lo && h[i].hi == h[i + 1].hi) {
      const bool flip = h[i].forward == h[i + 1].forward;  // same direction: one of them must turn over
      neighbours[static_cast<std::size_t>(h[i].face)].push_back({h[i + 1].face, flip});
      neighbours[static_cast<std::size_t>(h[i + 1].face)].push_back({h[i].face, flip});
    }
  std::vector<signed char> state(face_count, -1);
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < face_count; ++seed) {
    if (state[seed] >= 0) continue;
    state[seed] = 0;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      for (const auto& [g, flip] : neighbours[f]) {
        const signed char want = static_cast<signed char>(state[f] ^ static_cast<signed char>(flip));
        auto& s = state[static_cast<std::size_t>(g)];
        if (s < 0) {
          s = want;
          stack.push_back(static_cast<std::size_t>(g));
        } else if (s != want) {
          return false;
        }
      }
    }
  }
  return true;
}

}  // namespace

MeshTopology mesh_topology(const Eigen::MatrixX3i& F, Eigen::Index vertex_count) {
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= vertex_count))
    throw InvalidInput("mesh face refers to a vertex index outside [0, " + std::to_string(vertex_count) + ")");
  MeshTopology t;
  t.vertices = static_cast<std::size_t>(vertex_count);
  t.faces = static_cast<std::size_t>(F.rows());

  std::vector<char> used(t.vertices, 0);
  UnionFind components(t.vertices);
  std::vector<std::array<int, 3>> sorted_faces;
  for (int f = 0; f < F.rows(); ++f) {
    std::array<int, 3> v{F(f, 0), F(f, 1), F(f, 2)};
    for (const int i : v) used[static_cast<std::size_t>(i)] = 1;
    components.unite(static_cast<std::size_t>(v[0]), static_cast<std::size_t>(v[1]));
    components.unite(static_cast<std::size_t>(v[0]), static_cast<std::size_t>(v[2]));
    std::sort(v.begin(), v.end());
    if (v[0] == v[1] || v[1] == v[2]) ++t.degenerate_faces;
    sorted_faces.push_back(v);
  }
  std::sort(sorted_faces.begin(), sorted_faces.end());
  for (std::size_t i = 1; i < sorted_faces.size(); ++i) t.duplicate_faces += sorted_faces[i] == sorted_faces[i - 1];

  std::size_t used_count = 0;
  for (std::size_t v = 0; v < t.vertices; ++v) {
    if (!used[v]) continue;
    ++used_count;
    t.components += components.find(v) == v;
  }
  t.isolated_vertices = t.vertices - used_count;

  const std::vector<HalfEdge> h = half_edges(F);
  bool consistent = true;
  UnionFind loops(t.vertices);
  std::size_t boundary_vertices_joined = 0;
  std::vector<char> on_boundary(t.vertices, 0);
  for (std::size_t begin = 0; begin < h.size();) {
    std::size_t end = begin;
    while (end < h.size() && h[end].lo == h[begin].lo && h[end].hi == h[begin].hi) ++end;
    ++t.edges;
    const std::size_t n = end - begin;
    if (n == 1) {
      ++t.boundary_edges;
      on_boundary[static_cast<std::size_t>(h[begin].lo)] = on_boundary[static_cast<std::size_t>(h[begin].hi)] = 1;
      boundary_vertices_joined += loops.unite(static_cast<std::size_t>(h[begin].lo), static_cast<std::size_t>(h[begin].hi));
    } else if (n > 2) {
      ++t.non_manifold_edges;
    } else if (h[begin].forward == h[begin + 1].forward) {
      consistent = false;
    }
    begin = end;
  }
  const std::size_t boundary_vertex_count = static_cast<std::size_t>(std::count(on_boundary.begin(), on_boundary.end(), 1));
  t.boundary_loops = boundary_vertex_count - boundary_vertices_joined;
  t.non_manifold_vertices = count_non_manifold_vertices(F);
  t.euler_characteristic = static_cast<long long>(used_count) - static_cast<long long>(t.edges) + static_cast<long long>(t.faces);

  t.closed = t.faces > 0 && t.boundary_edges == 0 && t.non_manifold_edges == 0;
  t.manifold = t.faces > 0 && t.non_manifold_edges == 0 && t.non_manifold_vertices == 0 && t.degenerate_faces == 0 &&
               t.duplicate_faces == 0;
  t.oriented = t.manifold && consistent;
  t.orientable = t.manifold && (consistent || orientable(h, t.faces));
  if (t.orientable) {
    const long long twice_genus = 2 * static_cast<long long>(t.components) - t.euler_characteristic -
                                  static_cast<long long>(t.boundary_loops);
    t.genus = twice_genus / 2;
  }
  return t;
}

}  // namespace scanstation
