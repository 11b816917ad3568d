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
  bool root(std::size_t x) const { return parent_[x] == x; }
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
  signed char at; // the face's corner k at which the half-edge starts (F(face, k) → F(face, k + 1))
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
  for (std::size_t k = 0; k < keys; ++k) {
    const auto first = out.begin() + static_cast<std::ptrdiff_t>(start[k]);
    const auto last = out.begin() + static_cast<std::ptrdiff_t>(start[k + 1]);
    if (last - first > 16) {
      std::sort(first, last, less);
      continue;
    }
    for (auto i = first + (first != last); i < last; ++i)  // a few items: insertion sort
      for (auto j = i; j != first && less(*j, *(j - 1)); --j) std::iter_swap(j, j - 1);
  }
  return out;
}

std::vector<HalfEdge> half_edges(const Eigen::MatrixX3i& F, std::size_t vertex_count) {
  std::vector<HalfEdge> h;
  h.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b) h.push_back({std::min(a, b), std::max(a, b), f, a < b, static_cast<signed char>(k)});
    }
  std::vector<std::size_t> start;
  return sorted_by_key(
      h, vertex_count, [](const HalfEdge& e) { return static_cast<std::size_t>(e.lo); },
      [](const HalfEdge& a, const HalfEdge& b) { return a < b; }, start);
}

// Faces around each vertex must form a single fan (edge-connected through
// edges at that vertex), else the vertex is non-manifold. The fans are the
// parts of a union-find over the corners (3f + k): corners of one face at
// one vertex are one, and the faces of an edge (v, w) join their corners at
// v and at w (an edge (v, v) of faces that repeat v joins them at v).
// `h` holds the half-edges sorted by edge (half_edges).
std::size_t count_non_manifold_vertices(const Eigen::MatrixX3i& F, const std::vector<HalfEdge>& h,
                                        std::size_t vertex_count) {
  const std::size_t corners = 3 * static_cast<std::size_t>(F.rows());
  UnionFind fans(corners);
  const auto corner = [&](int f, int v) {
    int k = 0;
    while (F(f, k) != v) ++k;
    return 3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(k);
  };
  std::vector<std::pair<int, int>> repeated;  // (v, face) for faces that repeat v
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      for (int j = k + 1; j < 3; ++j)
        if (F(f, k) == F(f, j)) {
          fans.unite(3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(k),
                     3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(j));
          repeated.emplace_back(F(f, k), f);
        }
  std::sort(repeated.begin(), repeated.end());
  for (std::size_t i = 1; i < repeated.size(); ++i)
    if (repeated[i].first == repeated[i - 1].first)
      fans.unite(corner(repeated[i].second, repeated[i].first), corner(repeated[i - 1].second, repeated[i].first));
  // The corners of a half-edge's ends: it runs from corner `at` to the next.
  const auto lo_corner = [](const HalfEdge& e) {
    return 3 * static_cast<std::size_t>(e.face) + static_cast<std::size_t>(e.forward ? e.at : (e.at + 1) % 3);
  };
  const auto hi_corner = [](const HalfEdge& e) {
    return 3 * static_cast<std::size_t>(e.face) + static_cast<std::size_t>(e.forward ? (e.at + 1) % 3 : e.at);
  };
  for (std::size_t i = 1; i < h.size(); ++i)
    if (h[i].lo == h[i - 1].lo && h[i].hi == h[i - 1].hi) {
      fans.unite(lo_corner(h[i]), lo_corner(h[i - 1]));
      fans.unite(hi_corner(h[i]), hi_corner(h[i - 1]));
    }
  std::vector<unsigned char> count(vertex_count, 0);  // fans at each vertex, up to 2
  std::size_t non_manifold = 0;
  for (std::size_t c = 0; c < corners; ++c)
    if (fans.root(c)) {
      unsigned char& n = count[static_cast<std::size_t>(F(static_cast<Eigen::Index>(c / 3), static_cast<Eigen::Index>(c % 3)))];
      non_manifold += n == 1;
      n = static_cast<unsigned char>(std::min(2, n + 1));
    }
  return non_manifold;
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

void require_face_indices(const Eigen::MatrixX3i& F, Eigen::Index vertex_count) {
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= vertex_count))
    throw InvalidInput("mesh face refers to a vertex index outside [0, " + std::to_string(vertex_count) + ")");
}

MeshTopology mesh_topology(const Eigen::MatrixX3i& F, Eigen::Index vertex_count) {
  require_face_indices(F, vertex_count);
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
  t.non_manifold_vertices = count_non_manifold_vertices(F, h, t.vertices);
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
