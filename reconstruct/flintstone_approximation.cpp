#include "reconstruct/flintstone_approximation.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

namespace scanstation {

namespace {

/// Errors e1 and e2 of replacing chain p … s by the edge v_p v_s.
void chain_errors(const FlintstoneTree2& tree, const Chain2& chain, ApproximationErrors& errors) {
  const Eigen::Vector2d a = tree.point(chain.p), b = tree.point(chain.s), ab = b - a;
  const double length2 = ab.squaredNorm();
  for (int k = chain.p + 1; k < chain.s; ++k) {
    const Eigen::Vector2d x = tree.point(k) - a;
    const double t = length2 > 0.0 ? std::clamp(x.dot(ab) / length2, 0.0, 1.0) : 0.0;
    errors.e1 = std::max(errors.e1, (x - t * ab).norm());
    const double line = length2 > 0.0 ? std::abs(ab.x() * x.y() - ab.y() * x.x()) / std::sqrt(length2) : x.norm();
    errors.e2 = std::max(errors.e2, line);
  }
}

/// In-order walk that refines a chain's node when `refine` says so.
PolygonApproximation approximate(const FlintstoneTree2& tree, const std::function<bool(const FlintstoneNode2&)>& refine) {
  PolygonApproximation result;
  std::vector<Chain2> stack;
  const auto tops = tree.top_chains();
  stack.push_back(tops[1]);
  stack.push_back(tops[0]);
  while (!stack.empty()) {
    const Chain2 chain = stack.back();
    stack.pop_back();
    if (chain.node >= 0) {
      const FlintstoneNode2& node = tree.nodes[static_cast<std::size_t>(chain.node)];
      if (refine(node)) {
        result.level = std::max(result.level, node.depth);
        const auto children = tree.children(node);
        stack.push_back(children[1]);
        stack.push_back(children[0]);
        continue;
      }
      result.errors.e5 = std::max(result.errors.e5, node.stone.width());
    }
    result.vertices.push_back(tree.vertex(chain.p));
    result.pieces.push_back(chain);
    chain_errors(tree, chain, result.errors);
  }
  return result;
}

/// Distance from x to triangle a b c (closest point by regions, Ericson §5.1.5).
double point_triangle_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ax = x - a;
  const double d1 = ab.dot(ax), d2 = ac.dot(ax);
  if (d1 <= 0 && d2 <= 0) return ax.norm();
  const Eigen::Vector3d bx = x - b;
  const double d3 = ab.dot(bx), d4 = ac.dot(bx);
  if (d3 >= 0 && d4 <= d3) return bx.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (x - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cx = x - c;
  const double d5 = ab.dot(cx), d6 = ac.dot(cx);
  if (d6 >= 0 && d5 <= d6) return cx.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (x - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (x - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denominator = 1.0 / (va + vb + vc);
  return (x - (a + ab * vb * denominator + ac * vc * denominator)).norm();
}

/// Errors e1 and e2 of replacing the node's faces by its approximating
/// triangles: each original vertex against the nearest of them.
void node_errors(const FlintstoneTree3& tree, const FlintstoneNode3& node, const std::vector<Eigen::RowVector3i>& triangles,
                 ApproximationErrors& errors) {
  const auto point = [&](int v) { return Eigen::Vector3d(tree.vertices.row(v).transpose()); };
  std::vector<Eigen::RowVector3i> pieces = triangles;
  if (pieces.empty()) pieces.emplace_back(node.corners[0], node.corners[1], node.corners[2]);
  for (int k = 0; k < node.face_count; ++k)
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d x = point(tree.faces(tree.face_order[static_cast<std::size_t>(node.first_face + k)], j));
      double e1 = std::numeric_limits<double>::infinity(), e2 = e1;
      for (const Eigen::RowVector3i& t : pieces) {
        const Eigen::Vector3d a = point(t(0)), b = point(t(1)), c = point(t(2));
        const Eigen::Vector3d normal = (b - a).cross(c - a);
        const double area2 = normal.norm();
        e1 = std::min(e1, point_triangle_distance(x, a, b, c));
        e2 = std::min(e2, area2 > 0.0 ? std::abs(normal.dot(x - a)) / area2 : (x - a).norm());
      }
      errors.e1 = std::max(errors.e1, e1);
      errors.e2 = std::max(errors.e2, e2);
    }
}

std::uint64_t undirected_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

/// Crack-free approximating triangles of a set of nodes that partitions the
/// faces (§7.3.2: "the approximation never cracks"). A node's piece of
/// surface is approximated by the polygon of the marked vertices along its
/// boundary, and the marks are global: every node's corners, every vertex
/// where three or more nodes meet or a node's boundary touches itself. So a
/// side split (or a corner a fallback split or coalescing paths produced)
/// appears in both nodes sharing that boundary, each boundary stretch between
/// marks becomes one edge used once in each direction, and the polygons,
/// triangulated by ears whose diagonals are new edges, close up. Stretches
/// that would give one edge twice (parallel stretches between the same two
/// marks, loops) are marked in their middle until no edge repeats.
class Stitcher {
 public:
  Stitcher(const FlintstoneTree3& tree, const std::vector<int>& nodes)
      : tree_(tree), F_(tree.faces), region_(static_cast<std::size_t>(F_.rows()), -1),
        marked_(static_cast<std::size_t>(tree.vertices.rows()), 0) {
    for (std::size_t r = 0; r < nodes.size(); ++r) {
      const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(nodes[r])];
      for (int k = 0; k < node.face_count; ++k)
        region_[static_cast<std::size_t>(tree.face_order[static_cast<std::size_t>(node.first_face + k)])] = static_cast<int>(r);
      for (const int c : node.corners) marked_[static_cast<std::size_t>(c)] = 1;
    }
    opposite_faces();
    mark_junctions();
    walk_boundaries(nodes.size());
    separate_repeated_stretches();
    region_normals(nodes.size());
    region_euler(tree, nodes);
  }

  /// Triangles of region r, oriented like the faces.
  /// A node keeps its topology where it can: all its boundary cycles are
  /// joined by bridge edges (walked in both directions) into one polygon
  /// whose ears are clipped — the Euler characteristic of that triangulation
  /// is d − m + 1 + bridges (d distinct vertices, m polygon entries). When that
  /// differs from the node's own (V − E + F of its faces), the node's boundary
  /// touches itself like a figure eight: such cycles are split at repeated
  /// vertices and the largest piece of each cycle is bridged.
  std::vector<Eigen::RowVector3i> triangles(int r) {
    std::vector<Eigen::RowVector3i> result;
    const Eigen::Vector3d& normal = normals_[static_cast<std::size_t>(r)];
    std::vector<std::vector<int>> cycles;
    long target = euler_[static_cast<std::size_t>(r)];
    for (const std::vector<int>& walk : walks_[static_cast<std::size_t>(r)]) {
      std::vector<int> cycle = marks_on(walk);
      std::vector<int> distinct = cycle;
      std::sort(distinct.begin(), distinct.end());
      if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() < 3) ++target;  // left out: a filled hole
      else cycles.push_back(std::move(cycle));
    }
    std::vector<int> everything;
    std::size_t entries = 0;
    for (const auto& cycle : cycles) {
      entries += cycle.size();
      everything.insert(everything.end(), cycle.begin(), cycle.end());
    }
    std::sort(everything.begin(), everything.end());
    const long distinct = std::unique(everything.begin(), everything.end()) - everything.begin();
    const long bridges = cycles.empty() ? 0 : static_cast<long>(cycles.size()) - 1;
    const bool whole = distinct - static_cast<long>(entries + 2 * static_cast<std::size_t>(bridges)) + 1 + bridges == target;
    std::vector<int> joined;
    for (std::vector<int>& cycle : cycles) {
      if (whole) {
        if (joined.empty()) joined = std::move(cycle);
        else bridge(joined, cycle);
        continue;
      }
      std::vector<std::vector<int>> polygons = simple_polygons(cycle);
      const auto largest = std::max_element(polygons.begin(), polygons.end(),
                                            [](const auto& a, const auto& b) { return a.size() < b.size(); });
      for (auto it = polygons.begin(); it != polygons.end(); ++it)
        if (it->size() >= 3 && it != largest) clip_ears(*it, normal, result);
      if (largest->size() < 3) continue;
      if (joined.empty()) joined = std::move(*largest);
      else bridge(joined, *largest);
    }
    if (!joined.empty()) clip_ears(joined, normal, result);
    return result;
  }

 private:
  Eigen::Vector3d point(int v) const { return tree_.vertices.row(v).transpose(); }

  /// The face across each edge, found among the faces around its end vertex.
  void opposite_faces() {
    const auto V = static_cast<std::size_t>(tree_.vertices.rows());
    std::vector<int> start(V + 1, 0), around(static_cast<std::size_t>(3 * F_.rows()));
    for (int f = 0; f < F_.rows(); ++f)
      for (int k = 0; k < 3; ++k) ++start[static_cast<std::size_t>(F_(f, k)) + 1];
    for (std::size_t v = 1; v <= V; ++v) start[v] += start[v - 1];
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int f = 0; f < F_.rows(); ++f)
      for (int k = 0; k < 3; ++k) around[static_cast<std::size_t>(fill[static_cast<std::size_t>(F_(f, k))]++)] = f;
    across_.resize(static_cast<std::size_t>(3 * F_.rows()));
    for (int f = 0; f < F_.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = F_(f, k), b = F_(f, (k + 1) % 3);
        for (int j = start[static_cast<std::size_t>(b)]; j < start[static_cast<std::size_t>(b) + 1]; ++j) {
          const int g = around[static_cast<std::size_t>(j)];
          if ((F_(g, 0) == b && F_(g, 1) == a) || (F_(g, 1) == b && F_(g, 2) == a) || (F_(g, 2) == b && F_(g, 0) == a))
            across_[static_cast<std::size_t>(3 * f + k)] = g;
        }
      }
  }

  bool on_boundary(int f, int k) const {
    return region_[static_cast<std::size_t>(f)] != region_[static_cast<std::size_t>(across_[static_cast<std::size_t>(3 * f + k)])];
  }

  /// Marks vertices around which three or more regions meet, or where a
  /// region's boundary passes more than once (more boundary edges leave the
  /// vertex than regions meet there).
  void mark_junctions() {
    const auto V = static_cast<std::size_t>(tree_.vertices.rows());
    std::vector<std::array<int, 3>> seen(V, {-1, -1, -1});
    std::vector<int> leaving(V, 0), regions(V, 0);
    for (int f = 0; f < F_.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const auto v = static_cast<std::size_t>(F_(f, k));
        const int r = region_[static_cast<std::size_t>(f)];
        auto& s = seen[v];
        if (std::find(s.begin(), s.end(), r) == s.end() && regions[v] < 3) s[static_cast<std::size_t>(regions[v]++)] = r;
        else if (std::find(s.begin(), s.end(), r) == s.end()) regions[v] = 4;
        leaving[v] += on_boundary(f, k);
      }
    for (std::size_t v = 0; v < V; ++v)
      if (regions[v] >= 3 || leaving[v] > regions[v]) marked_[v] = 1;
  }

  /// Each region's boundary cycles as vertex sequences, walked with the
  /// region on the left (turning around each vertex through the region's faces).
  void walk_boundaries(std::size_t regions) {
    walks_.assign(regions, {});
    std::vector<char> walked(static_cast<std::size_t>(3 * F_.rows()), 0);
    for (int f0 = 0; f0 < F_.rows(); ++f0)
      for (int k0 = 0; k0 < 3; ++k0) {
        if (walked[static_cast<std::size_t>(3 * f0 + k0)] || !on_boundary(f0, k0)) continue;
        std::vector<int> walk;
        int f = f0, k = k0;
        while (!walked[static_cast<std::size_t>(3 * f + k)]) {
          walked[static_cast<std::size_t>(3 * f + k)] = 1;
          walk.push_back(F_(f, k));
          const int w = F_(f, (k + 1) % 3);
          k = (k + 1) % 3;  // the edge of f leaving w
          while (!on_boundary(f, k)) {
            f = across_[static_cast<std::size_t>(3 * f + k)];
            k = 0;
            while (F_(f, k) != w) ++k;
          }
        }
        walks_[static_cast<std::size_t>(region_[static_cast<std::size_t>(f0)])].push_back(std::move(walk));
      }
  }

  /// The marked vertices of a boundary cycle, in order.
  std::vector<int> marks_on(const std::vector<int>& walk) const {
    std::vector<int> marks;
    for (const int v : walk)
      if (marked_[static_cast<std::size_t>(v)]) marks.push_back(v);
    return marks;
  }

  /// Stretches between consecutive marks give one edge each; where two
  /// different stretches join the same marks (or a stretch returns to its
  /// start), their inner vertices are marked, until every edge is unique.
  void separate_repeated_stretches() {
    struct Stretch {
      const std::vector<int>* walk;
      std::size_t from, to;  ///< positions of the marks; `to` may run past the end (cyclic)
      int at(std::size_t k) const { return (*walk)[k % walk->size()]; }
      /// The first step at the smaller end names the stretch from either side.
      std::uint64_t name() const {
        return at(from) < at(to) ? undirected_key(at(from), at(from + 1)) : undirected_key(at(to), at(to - 1));
      }
    };
    for (bool changed = true; changed;) {
      changed = false;
      const auto mark = [&](std::size_t v) { changed |= !marked_[v]; marked_[v] = 1; };
      std::unordered_map<std::uint64_t, Stretch> owner;  // edge → the stretch giving it
      owner.reserve(static_cast<std::size_t>(F_.rows()));
      for (const auto& cycles : walks_)
        for (const std::vector<int>& walk : cycles) {
          std::vector<std::size_t> at;
          for (std::size_t k = 0; k < walk.size(); ++k)
            if (marked_[static_cast<std::size_t>(walk[k])]) at.push_back(k);
          if (at.empty()) {  // a cycle without marks: three marks along it
            for (std::size_t k = 0; k < 3; ++k) mark(static_cast<std::size_t>(walk[k * walk.size() / 3]));
            continue;
          }
          for (std::size_t j = 0; j < at.size(); ++j) {
            const Stretch stretch{&walk, at[j], j + 1 < at.size() ? at[j + 1] : at.front() + walk.size()};
            const std::size_t length = stretch.to - stretch.from;
            const auto inner = [&](const Stretch& s, std::size_t part, std::size_t parts) {
              return static_cast<std::size_t>(s.at(s.from + part * (s.to - s.from) / parts));
            };
            if (stretch.at(stretch.from) == stretch.at(stretch.to)) {  // a loop: two inner marks
              if (length >= 3) {
                mark(inner(stretch, 1, 3));
                mark(inner(stretch, 2, 3));
              }
              continue;
            }
            const auto [it, fresh] = owner.emplace(undirected_key(stretch.at(stretch.from), stretch.at(stretch.to)), stretch);
            if (fresh || it->second.name() == stretch.name()) continue;
            // Two stretches, one edge: split the longer (a single edge cannot be split).
            const Stretch& longer = it->second.to - it->second.from > length ? it->second : stretch;
            if (longer.to - longer.from >= 2) mark(inner(longer, 1, 2));
          }
        }
      if (!changed)
        for (const auto& entry : owner) used_.insert(entry.first);
    }
  }

  /// Splits a cycle that visits a vertex twice into simple cycles.
  static std::vector<std::vector<int>> simple_polygons(const std::vector<int>& cycle) {
    std::vector<std::vector<int>> result;
    std::vector<int> stack;
    std::unordered_map<int, std::size_t> position;
    for (const int v : cycle) {
      const auto it = position.find(v);
      if (it != position.end()) {
        result.emplace_back(stack.begin() + static_cast<std::ptrdiff_t>(it->second), stack.end());
        for (std::size_t k = it->second + 1; k < stack.size(); ++k) position.erase(stack[k]);
        stack.resize(it->second + 1);
        continue;
      }
      position[v] = stack.size();
      stack.push_back(v);
    }
    result.push_back(std::move(stack));
    return result;
  }

  /// V − E + F of each region's faces.
  void region_euler(const FlintstoneTree3& tree, const std::vector<int>& nodes) {
    std::vector<int> stamp(static_cast<std::size_t>(tree.vertices.rows()), -1);
    euler_.assign(nodes.size(), 0);
    for (std::size_t r = 0; r < nodes.size(); ++r) {
      const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(nodes[r])];
      long vertices = 0, boundary = 0;
      for (int k = 0; k < node.face_count; ++k) {
        const int f = tree.face_order[static_cast<std::size_t>(node.first_face + k)];
        for (int j = 0; j < 3; ++j) {
          boundary += on_boundary(f, j);
          if (stamp[static_cast<std::size_t>(F_(f, j))] != static_cast<int>(r)) {
            stamp[static_cast<std::size_t>(F_(f, j))] = static_cast<int>(r);
            ++vertices;
          }
        }
      }
      euler_[r] = vertices - (3 * node.face_count + boundary) / 2 + node.face_count;
    }
  }

  /// Area-weighted normal of each region.
  void region_normals(std::size_t regions) {
    normals_.assign(regions, Eigen::Vector3d::Zero());
    for (int f = 0; f < F_.rows(); ++f)
      normals_[static_cast<std::size_t>(region_[static_cast<std::size_t>(f)])] +=
          (point(F_(f, 1)) - point(F_(f, 0))).cross(point(F_(f, 2)) - point(F_(f, 0)));
  }

  /// Joins `hole` into `polygon` by the shortest edge between them that is
  /// not an edge yet: … u, w, (hole from w), w, u, ….
  void bridge(std::vector<int>& polygon, const std::vector<int>& hole) {
    std::size_t best_u = 0, best_w = 0;
    std::pair<bool, double> best{true, std::numeric_limits<double>::infinity()};
    for (std::size_t i = 0; i < polygon.size(); ++i)
      for (std::size_t j = 0; j < hole.size(); ++j) {
        if (polygon[i] == hole[j]) continue;
        const std::pair<bool, double> score{used_.count(undirected_key(polygon[i], hole[j])) > 0,
                                            (point(polygon[i]) - point(hole[j])).squaredNorm()};
        if (score < best) {
          best = score;
          best_u = i;
          best_w = j;
        }
      }
    std::vector<int> merged(polygon.begin(), polygon.begin() + static_cast<std::ptrdiff_t>(best_u) + 1);
    for (std::size_t j = 0; j <= hole.size(); ++j) merged.push_back(hole[(best_w + j) % hole.size()]);
    merged.insert(merged.end(), polygon.begin() + static_cast<std::ptrdiff_t>(best_u), polygon.end());
    used_.insert(undirected_key(polygon[best_u], hole[best_w]));
    polygon = std::move(merged);
  }

  /// Ear clipping: prefers ears convex about the region's normal, then the
  /// shortest diagonal; a diagonal that is already an edge is never taken
  /// while another ear remains (it would be shared by four triangles).
  void clip_ears(std::vector<int> polygon, const Eigen::Vector3d& normal, std::vector<Eigen::RowVector3i>& out) {
    while (polygon.size() > 3) {
      const std::size_t n = polygon.size();
      std::size_t best = 0;
      std::tuple<bool, bool, double> best_score{true, true, std::numeric_limits<double>::infinity()};
      bool found = false;
      for (std::size_t k = 0; k < n; ++k) {
        const int p = polygon[(k + n - 1) % n], c = polygon[k], q = polygon[(k + 1) % n];
        if (p == q || p == c || c == q) continue;  // around a bridge end
        const bool repeated = used_.count(undirected_key(p, q)) > 0;
        const bool reflex = (point(c) - point(p)).cross(point(q) - point(c)).dot(normal) <= 0.0;
        const std::tuple<bool, bool, double> score{repeated, reflex, (point(q) - point(p)).squaredNorm()};
        if (!found || score < best_score) {
          best_score = score;
          best = k;
          found = true;
        }
      }
      if (!found) return;
      const int p = polygon[(best + n - 1) % n], c = polygon[best], q = polygon[(best + 1) % n];
      out.emplace_back(p, c, q);
      used_.insert(undirected_key(p, q));
      polygon.erase(polygon.begin() + static_cast<std::ptrdiff_t>(best));
    }
    if (polygon[0] != polygon[1] && polygon[1] != polygon[2] && polygon[2] != polygon[0])
      out.emplace_back(polygon[0], polygon[1], polygon[2]);
  }

  const FlintstoneTree3& tree_;
  const Eigen::MatrixX3i& F_;
  std::vector<int> region_;
  std::vector<char> marked_;
  std::vector<int> across_;
  std::vector<std::vector<std::vector<int>>> walks_;  ///< per region, its boundary cycles
  std::vector<Eigen::Vector3d> normals_;
  std::vector<long> euler_;
  std::unordered_set<std::uint64_t> used_;              ///< edges of the approximation so far
};

MeshApproximation approximate(const FlintstoneTree3& tree, const std::function<bool(const FlintstoneNode3&)>& refine) {
  MeshApproximation result;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(id)];
    if (!node.leaf() && (id == 0 || refine(node))) {
      result.level = std::max(result.level, node.depth);
      for (int c = node.child_count - 1; c >= 0; --c) stack.push_back(node.first_child + c);
      continue;
    }
    if (!node.leaf()) result.errors.e5 = std::max(result.errors.e5, node.stone.width());
    result.nodes.push_back(id);
  }
  Stitcher stitcher(tree, result.nodes);
  std::vector<Eigen::RowVector3i> faces;
  for (std::size_t r = 0; r < result.nodes.size(); ++r) {
    const std::vector<Eigen::RowVector3i> triangles = stitcher.triangles(static_cast<int>(r));
    node_errors(tree, tree.nodes[static_cast<std::size_t>(result.nodes[r])], triangles, result.errors);
    for (const Eigen::RowVector3i& t : triangles) {
      faces.push_back(t);
      result.pieces.push_back(result.nodes[r]);
    }
  }
  result.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t k = 0; k < faces.size(); ++k) result.faces.row(static_cast<Eigen::Index>(k)) = faces[k];
  return result;
}

}  // namespace

MeshApproximation approximation(const FlintstoneTree3& tree, int level) {
  if (level < 0) throw InvalidInput("approximation level must be ≥ 0, got " + std::to_string(level));
  return approximate(tree, [&](const FlintstoneNode3& node) { return node.depth <= level; });
}

MeshApproximation adaptive_approximation(const FlintstoneTree3& tree, double max_error) {
  if (!(max_error >= 0.0)) throw InvalidInput("approximation error bound must be ≥ 0");
  return approximate(tree, [&](const FlintstoneNode3& node) { return node.stone.width() > max_error; });
}

PolygonApproximation approximation(const FlintstoneTree2& tree, int level) {
  if (level < 0) throw InvalidInput("approximation level must be ≥ 0, got " + std::to_string(level));
  return approximate(tree, [&](const FlintstoneNode2& node) { return node.depth <= level; });
}

PolygonApproximation adaptive_approximation(const FlintstoneTree2& tree, double max_error) {
  if (!(max_error >= 0.0)) throw InvalidInput("approximation error bound must be ≥ 0");
  return approximate(tree, [&](const FlintstoneNode2& node) { return node.stone.width() > max_error; });
}

}  // namespace scanstation
