#include "core/mesh_topology.h"

#include "core/errors.h"

#include <algorithm>
#include <array>
#include <functional>
#include <numeric>
#include <tuple>
#include <vector>

namespace scanstation {

namespace {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n = 0) { reset(n); }
  // n singletons again, reusing the storage (one union-find per vertex's fan).
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
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

// Sorts `items` by key(item), a number in [0, keys), then each run of equal
// keys by `less`: a counting sort, linear, and then sorts of runs a few
// items long (a vertex's corners or edges), instead of one sort of all the
// items (on a 75k-face mesh the three sorts were most of this check's time).
// `start` gets each key's first item (keys + 1 entries).
template <typename T, typename Key, typename Less>
std::vector<T> sorted_by_key(const std::vector<T>& items, std::size_t keys, Key&& key, Less&& less,
                             std::vector<std::size_t>& start) {
  start.assign(keys + 1, 0);
  for (const T& item : items) ++start[key(item) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<T> out(items.size());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (const T& item : items) out[next[key(item)]++] = item;
  for (std::size_t k = 0; k < keys; ++k)
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(start[k]), out.begin() + static_cast<std::ptrdiff_t>(start[k + 1]), less);
  return out;
}

std::vector<HalfEdge> half_edges(const Eigen::MatrixX3i& F, std::size_t vertex_count) {
  std::vector<HalfEdge> h;
  h.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b) h.push_back({std::min(a, b), std::max(a, b), f, a < b});
    }
  std::vector<std::size_t> start;
  return sorted_by_key(
      h, vertex_count, [](const HalfEdge& e) { return static_cast<std::size_t>(e.lo); },
      [](const HalfEdge& a, const HalfEdge& b) { return a < b; }, start);
}

// Faces around each vertex must form a single fan (edge-connected through
// edges at that vertex), else the vertex is non-manifold.
std::size_t count_non_manifold_vertices(const Eigen::MatrixX3i& F, std::size_t vertex_count) {
  struct Corner {
    int vertex, other, face;  // the face has the edge vertex–other
  };
  std::vector<Corner> corners;
  corners.reserve(static_cast<std::size_t>(F.rows()) * 6);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      corners.push_back({F(f, k), F(f, (k + 1) % 3), f});
      corners.push_back({F(f, k), F(f, (k + 2) % 3), f});
    }
  std::vector<std::size_t> start;
  // At each vertex by other vertex: corners sharing one share an edge at the vertex.
  corners = sorted_by_key(
      corners, vertex_count, [](const Corner& c) { return static_cast<std::size_t>(c.vertex); },
      [](const Corner& a, const Corner& b) { return std::tie(a.other, a.face) < std::tie(b.other, b.face); }, start);
  std::size_t count = 0;
  std::vector<int> faces;
  UnionFind fans;
  for (std::size_t v = 0; v < vertex_count; ++v) {
    if (start[v] == start[v + 1]) continue;
    faces.clear();
    for (std::size_t i = start[v]; i < start[v + 1]; ++i) faces.push_back(corners[i].face);
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    fans.reset(faces.size());
    std::size_t groups = faces.size();
    const auto local = [&](int f) { return static_cast<std::size_t>(std::lower_bound(faces.begin(), faces.end(), f) - faces.begin()); };
    for (std::size_t i = start[v] + 1; i < start[v + 1]; ++i)
      if (corners[i].other == corners[i - 1].other && fans.unite(local(corners[i].face), local(corners[i - 1].face)))
        --groups;
    if (groups > 1) ++count;
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
  sorted_faces.reserve(t.faces);
  for (int f = 0; f < F.rows(); ++f) {
    std::array<int, 3> v{F(f, 0), F(f, 1), F(f, 2)};
    for (const int i : v) used[static_cast<std::size_t>(i)] = 1;
    components.unite(static_cast<std::size_t>(v[0]), static_cast<std::size_t>(v[1]));
    components.unite(static_cast<std::size_t>(v[0]), static_cast<std::size_t>(v[2]));
    std::sort(v.begin(), v.end());
    if (v[0] == v[1] || v[1] == v[2]) ++t.degenerate_faces;
    sorted_faces.push_back(v);
  }
  std::vector<std::size_t> start;
  sorted_faces = sorted_by_key(
      sorted_faces, t.vertices, [](const std::array<int, 3>& v) { return static_cast<std::size_t>(v[0]); },
      std::less<std::array<int, 3>>(), start);
  for (std::size_t i = 1; i < sorted_faces.size(); ++i) t.duplicate_faces += sorted_faces[i] == sorted_faces[i - 1];

  std::size_t used_count = 0;
  for (std::size_t v = 0; v < t.vertices; ++v) {
    if (!used[v]) continue;
    ++used_count;
    t.components += components.find(v) == v;
  }
  t.isolated_vertices = t.vertices - used_count;

  const std::vector<HalfEdge> h = half_edges(F, t.vertices);
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
  t.non_manifold_vertices = count_non_manifold_vertices(F, t.vertices);
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
