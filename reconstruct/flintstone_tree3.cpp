#include "reconstruct/flintstone_tree3.h"

#include "core/errors.h"
#include "core/mesh_topology.h"
#include "reconstruct/smallest_enclosing_ball.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <queue>
#include <unordered_map>
#include <unordered_set>

namespace scanstation {

namespace {

using Triple = std::array<int, 3>;

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
std::uint64_t undirected_key(int a, int b) { return edge_key(std::min(a, b), std::max(a, b)); }

/// Face across each edge k (from F(f,k) to F(f,k+1)) of each face f.
std::vector<int> face_neighbors(const Eigen::MatrixX3i& F) {
  std::unordered_map<std::uint64_t, int> half_edges;
  half_edges.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (!half_edges.emplace(edge_key(F(f, k), F(f, (k + 1) % 3)), f).second)
        throw TopologyError("flintstone tree: edge " + std::to_string(F(f, k)) + "–" +
                            std::to_string(F(f, (k + 1) % 3)) +
                            " is used twice in the same direction (mesh not manifold or not oriented)");
  std::vector<int> neighbor(static_cast<std::size_t>(3 * F.rows()));
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto it = half_edges.find(edge_key(F(f, (k + 1) % 3), F(f, k)));
      if (it == half_edges.end())
        throw TopologyError("flintstone tree: the mesh is not closed (edge " + std::to_string(F(f, k)) + "–" +
                            std::to_string(F(f, (k + 1) % 3)) + " has one face)");
      neighbor[static_cast<std::size_t>(3 * f + k)] = it->second;
    }
  return neighbor;
}

/// A ball through three vertices holding all vertices (§7.3.2): the smallest
/// bounding ball when it touches three, otherwise that ball grown away from
/// its two touching vertices until it touches a third.
Triple root_corners(const Eigen::MatrixX3d& V, Eigen::Vector3d& center, double& radius) {
  const EnclosingBall<3> ball = smallest_enclosing_ball<3>(V);
  center = ball.center;
  radius = ball.radius;
  const auto area = [&](int a, int b, int c) {
    return (V.row(b) - V.row(a)).cross(V.row(c) - V.row(a)).squaredNorm();
  };
  Triple best = {-1, -1, -1};
  double best_area = 0.0;
  const auto& s = ball.support;
  for (std::size_t a = 0; a < s.size(); ++a)
    for (std::size_t b = a + 1; b < s.size(); ++b)
      for (std::size_t c = b + 1; c < s.size(); ++c)
        if (area(s[a], s[b], s[c]) > best_area) {
          best_area = area(s[a], s[b], s[c]);
          best = {s[a], s[b], s[c]};
        }
  if (best[0] >= 0) return best;
  if (s.size() < 2) throw InvalidInput("flintstone tree: all vertices coincide");
  const int i = s[0], j = s[1];
  const Eigen::Vector3d m = 0.5 * (V.row(i) + V.row(j)).transpose();
  const Eigen::Vector3d axis = (V.row(j) - V.row(i)).transpose().normalized();
  Eigen::Vector3d away = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    Eigen::Vector3d u = V.row(v).transpose() - m;
    u -= u.dot(axis) * axis;
    if (u.squaredNorm() > away.squaredNorm()) away = u;
  }
  if (away.squaredNorm() == 0.0) throw InvalidInput("flintstone tree: all vertices lie on one line");
  const Eigen::Vector3d d = -away.normalized();
  const double rho2 = (V.row(i).transpose() - m).squaredNorm();
  // Centre m + t·d: v stays inside while t ≤ (ρ² − |u|²) / (−2 u·d) for u·d < 0.
  double t_min = std::numeric_limits<double>::infinity();
  int k = -1;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const Eigen::Vector3d u = V.row(v).transpose() - m;
    const double ud = u.dot(d);
    if (ud >= 0.0 || v == i || v == j) continue;
    const double t = std::max(0.0, (rho2 - u.squaredNorm()) / (-2.0 * ud));
    if (t < t_min) {
      t_min = t;
      k = static_cast<int>(v);
    }
  }
  center = m + t_min * d;
  radius = std::sqrt(rho2 + t_min * t_min);
  return {i, j, k};
}

class Builder {
 public:
  Builder(FlintstoneTree3& tree, const FlintstoneOptions3& options)
      : tree_(tree),
        options_(options),
        V_(tree.vertices),
        F_(tree.faces),
        neighbor_(face_neighbors(tree.faces)),
        face_mark_(static_cast<std::size_t>(F_.rows()), -1),
        face_label_(static_cast<std::size_t>(F_.rows()), -1),
        face_half_(static_cast<std::size_t>(F_.rows()), -1),
        local_(static_cast<std::size_t>(V_.rows()), -1),
        boundary_mark_(static_cast<std::size_t>(V_.rows()), -1),
        next_(static_cast<std::size_t>(V_.rows()), -1),
        eligible_(static_cast<std::size_t>(V_.rows()), 0) {}

  void run() {
    FlintstoneNode3 root;
    Eigen::Vector3d center;
    double radius = 0.0;
    // The corners must lie on the surface: isolated vertices are left out.
    std::vector<char> used(static_cast<std::size_t>(V_.rows()), 0);
    for (Eigen::Index f = 0; f < F_.rows(); ++f)
      for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(F_(f, k))] = 1;
    std::vector<int> on_surface;
    for (int v = 0; v < V_.rows(); ++v)
      if (used[static_cast<std::size_t>(v)]) on_surface.push_back(v);
    const Eigen::MatrixX3d surface = V_(on_surface, Eigen::all);
    root.corners = root_corners(surface, center, radius);
    for (int& corner : root.corners) corner = on_surface[static_cast<std::size_t>(corner)];
    const double reach = (V_.rowwise() - center.transpose()).rowwise().norm().maxCoeff();
    root.stone = ball_flintstone<3>(center, std::max(radius, reach));
    root.bound = root.stone.first;
    root.box = vertex_box(on_surface);
    root.face_count = static_cast<int>(F_.rows());
    tree_.face_order.resize(static_cast<std::size_t>(F_.rows()));
    for (int f = 0; f < F_.rows(); ++f) tree_.face_order[static_cast<std::size_t>(f)] = f;
    tree_.nodes.push_back(root);
    candidates_.push_back({});
    execute(0, prepare(0), {});
    refine_levels(1);
  }

  /// Rebuilds the subtree of node `id` (§7.5) over its current face range,
  /// keeping its corners; the old descendants become unreachable.
  void rebuild(int id) {
    candidates_.assign(tree_.nodes.size(), {});
    candidates_[static_cast<std::size_t>(id)] = {tree_.nodes[static_cast<std::size_t>(id)].corners};
    tree_.nodes[static_cast<std::size_t>(id)].child_count = 0;
    const std::size_t first_new = tree_.nodes.size();
    execute(id, prepare(id), {});
    refine_levels(first_new);
  }

 private:
  struct Cut {
    int from, to;
  };

  Eigen::Vector3d point(int v) const { return V_.row(v).transpose(); }
  int face_vertex(int f, int k) const { return F_(f, k); }
  int neighbor(int f, int k) const { return neighbor_[static_cast<std::size_t>(3 * f + k)]; }

  /// What a node will do, decided before its level's side splits are
  /// propagated to the neighbours (§7.3.2).
  struct Plan {
    bool leaf = false;
    int split = -1;                            ///< v_q / v_r, -1 when P has no interior vertex
    std::array<int, 3> side_vertex{-1, -1, -1};  ///< balanced vertex of side k (c[k] … c[k+1]), -1: one edge
    std::array<bool, 3> sides{};               ///< sides the node itself splits
    bool three = false;                        ///< a three-split at `split`
  };

  /// Faces, boundary, corners, flintstone and the node's own split decision.
  Plan prepare(int id) {
    FlintstoneNode3 node = tree_.nodes[static_cast<std::size_t>(id)];
    Plan plan;
    const auto faces = face_range(node);
    for (const int f : faces) face_mark_[static_cast<std::size_t>(f)] = id;
    node.first_boundary = static_cast<int>(tree_.boundary.size());
    for (const int f : faces)
      for (int k = 0; k < 3; ++k)
        if (face_mark_[static_cast<std::size_t>(neighbor(f, k))] != id)
          tree_.boundary.push_back({face_vertex(f, k), face_vertex(f, (k + 1) % 3)});
    node.boundary_count = static_cast<int>(tree_.boundary.size()) - node.first_boundary;
    if (id != 0) node.corners = choose_corners(id, node);
    if (faces.size() == 1) {
      const int f = faces.front();
      node.corners = {face_vertex(f, 0), face_vertex(f, 1), face_vertex(f, 2)};
      node.stone = enclosing_flintstone<3>(V_, {node.corners.begin(), node.corners.end()});
      node.bound = node.stone.first;
      node.box = vertex_box({node.corners.begin(), node.corners.end()});
      tree_.nodes[static_cast<std::size_t>(id)] = node;
      plan.leaf = true;
      return plan;
    }
    if (id != 0) {
      gather_vertices(faces);
      node.bound = enclosing_flintstone<3>(V_, vertices_).first;
      node.box = vertex_box(vertices_);
      for (const int v : vertices_) eligible_[static_cast<std::size_t>(v)] = boundary_mark_[static_cast<std::size_t>(v)] != id;
      node.stone = flintstone_of<3>(V_, node.corners, vertices_, plan.split, &eligible_);
      for (const int v : vertices_) {
        eligible_[static_cast<std::size_t>(v)] = 0;
        local_[static_cast<std::size_t>(v)] = -1;
      }
      for (int k = 0; k < 3; ++k)
        plan.side_vertex[static_cast<std::size_t>(k)] = side_split_vertex(
            node, node.corners[static_cast<std::size_t>(k)], node.corners[static_cast<std::size_t>((k + 1) % 3)], node.corners);
      plan_split(node, plan);
    }
    tree_.nodes[static_cast<std::size_t>(id)] = node;
    return plan;
  }

  /// Cuts the node as planned — at every side a neighbour splits too
  /// (`split_sides`: side key → vertex), so shared sides split alike — and
  /// appends its children.
  void execute(int id, const Plan& plan, const std::unordered_map<std::uint64_t, int>& split_sides) {
    if (plan.leaf) return;
    FlintstoneNode3 node = tree_.nodes[static_cast<std::size_t>(id)];
    const Triple c = node.corners;
    std::vector<Cut> cuts;
    std::vector<Triple> children;
    std::array<bool, 3> sides = plan.sides;
    for (int k = 0; k < 3; ++k) {
      const auto it = split_sides.find(undirected_key(c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>((k + 1) % 3)]));
      if (it != split_sides.end() && it->second == plan.side_vertex[static_cast<std::size_t>(k)]) sides[static_cast<std::size_t>(k)] = true;
    }
    if (id == 0) {
      cuts = {{c[0], c[1]}, {c[1], c[2]}, {c[2], c[0]}};
      children = {{c[0], c[1], c[2]}, {c[2], c[1], c[0]}};
    } else if (std::count(sides.begin(), sides.end(), true) > 0) {
      ++tree_.stats.side_splits;
      side_split(c, plan.side_vertex, sides, cuts, children);
    } else if (plan.three) {
      ++tree_.stats.three_splits;
      cuts = {{plan.split, c[0]}, {plan.split, c[1]}, {plan.split, c[2]}};
      children = {{c[0], c[1], plan.split}, {c[1], c[2], plan.split}, {c[2], c[0], plan.split}};
    }
    const auto faces = face_range(node);
    gather_vertices(faces);
    std::vector<int> labels = label_components(faces, cuts);
    if (labels.empty()) {
      ++tree_.stats.fallback_splits;
      labels = halves(faces);
      children.clear();
    }
    for (const int v : vertices_) local_[static_cast<std::size_t>(v)] = -1;
    make_children(id, node, labels, children);
  }

  /// Refines all nodes from `begin` on, level by level: every node of a
  /// level decides first, then the sides any of them splits are split by
  /// both triangles that share them (no cracks, §7.3.2).
  void refine_levels(std::size_t begin) {
    while (begin < tree_.nodes.size()) {
      const std::size_t end = tree_.nodes.size();
      std::vector<Plan> plans;
      plans.reserve(end - begin);
      std::unordered_map<std::uint64_t, int> split_sides;
      for (std::size_t id = begin; id < end; ++id) {
        plans.push_back(prepare(static_cast<int>(id)));
        const Plan& plan = plans.back();
        const Triple& c = tree_.nodes[id].corners;
        for (int k = 0; k < 3; ++k)
          if (plan.sides[static_cast<std::size_t>(k)])
            split_sides[undirected_key(c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>((k + 1) % 3)])] =
                plan.side_vertex[static_cast<std::size_t>(k)];
      }
      for (std::size_t id = begin; id < end; ++id) execute(static_cast<int>(id), plans[id - begin], split_sides);
      begin = end;
    }
  }

  std::vector<int> face_range(const FlintstoneNode3& node) const {
    const auto begin = tree_.face_order.begin() + node.first_face;
    return {begin, begin + node.face_count};
  }

  /// vertices_ (local numbering in local_) and boundary_mark_ for node `id`.
  /// The box of `vertices`, widened so that float tests against it stay on
  /// the safe side.
  Eigen::AlignedBox3d vertex_box(const std::vector<int>& vertices) const {
    Eigen::AlignedBox3d box;
    for (const int v : vertices) box.extend(point(v));
    const double slack = 1e-9 * (box.sizes().maxCoeff() + box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).maxCoeff());
    box.min().array() -= slack;
    box.max().array() += slack;
    return box;
  }

  void gather_vertices(const std::vector<int>& faces) {
    vertices_.clear();
    for (const int f : faces)
      for (int k = 0; k < 3; ++k) {
        const int v = face_vertex(f, k);
        if (local_[static_cast<std::size_t>(v)] >= 0) continue;
        local_[static_cast<std::size_t>(v)] = static_cast<int>(vertices_.size());
        vertices_.push_back(v);
      }
  }

  /// Marks the boundary vertices of node `id` and links each to the next
  /// boundary vertex (next_), for walks along the boundary.
  void mark_boundary(int id, const FlintstoneNode3& node) {
    for (int e = 0; e < node.boundary_count; ++e) {
      const auto [a, b] = tree_.boundary[static_cast<std::size_t>(node.first_boundary + e)];
      boundary_mark_[static_cast<std::size_t>(a)] = id;
      next_[static_cast<std::size_t>(a)] = b;
    }
  }

  /// The boundary path from a to b (both on the boundary), empty when the
  /// walk does not reach b (a pinched boundary).
  std::vector<int> boundary_path(const FlintstoneNode3& node, int a, int b) const {
    std::vector<int> path{a};
    for (int steps = 0; steps < node.boundary_count && path.back() != b; ++steps)
      path.push_back(next_[static_cast<std::size_t>(path.back())]);
    if (path.back() != b) path.clear();
    return path;
  }

  /// The corners of a new node: of the candidate triangles its parent
  /// planned, the one with most vertices on the node's boundary, missing
  /// corners replaced by far boundary vertices, in boundary order.
  Triple choose_corners(int id, const FlintstoneNode3& node) {
    mark_boundary(id, node);
    const auto on_boundary = [&](int v) { return boundary_mark_[static_cast<std::size_t>(v)] == id; };
    Triple best = {-1, -1, -1};
    int best_hits = -1;
    for (const Triple& c : candidates_[static_cast<std::size_t>(id)]) {
      int hits = 0;
      for (const int v : c) hits += on_boundary(v);
      if (hits > best_hits) {
        best_hits = hits;
        best = c;
      }
    }
    std::vector<int> chosen;
    for (const int v : best)
      if (v >= 0 && on_boundary(v) && std::find(chosen.begin(), chosen.end(), v) == chosen.end()) chosen.push_back(v);
    if (chosen.empty()) chosen.push_back(tree_.boundary[static_cast<std::size_t>(node.first_boundary)][0]);
    while (chosen.size() < 3) {
      int far = -1;
      double far_distance = -1.0;
      for (int e = 0; e < node.boundary_count; ++e) {
        const int v = tree_.boundary[static_cast<std::size_t>(node.first_boundary + e)][0];
        if (std::find(chosen.begin(), chosen.end(), v) != chosen.end()) continue;
        double nearest = std::numeric_limits<double>::infinity();
        for (const int c : chosen) nearest = std::min(nearest, (point(v) - point(c)).squaredNorm());
        if (nearest > far_distance) {
          far_distance = nearest;
          far = v;
        }
      }
      if (far < 0) break;
      chosen.push_back(far);
    }
    while (chosen.size() < 3) chosen.push_back(chosen.back());
    // Boundary order keeps the approximating triangle oriented like the faces.
    Triple corners = {chosen[0], chosen[1], chosen[2]};
    int at = corners[0];
    for (int steps = 0; steps < node.boundary_count; ++steps) {
      at = next_[static_cast<std::size_t>(at)];
      if (at == corners[2]) {
        std::swap(corners[1], corners[2]);
        break;
      }
      if (at == corners[1]) break;
    }
    return corners;
  }

  /// Corner angle at corners[c] of the approximating triangle.
  double corner_angle(const Triple& corners, int c) const {
    const Eigen::Vector3d a = point(corners[static_cast<std::size_t>(c)]);
    const Eigen::Vector3d u = point(corners[static_cast<std::size_t>((c + 1) % 3)]) - a;
    const Eigen::Vector3d w = point(corners[static_cast<std::size_t>((c + 2) % 3)]) - a;
    return std::atan2(u.cross(w).norm(), u.dot(w));
  }

  /// The vertex of the boundary path a … b that best balances the lengths of
  /// the two new sides (§7.3.2); -1 when the path is a single edge.
  int side_split_vertex(const FlintstoneNode3& node, int a, int b, const Triple& corners) const {
    const std::vector<int> path = boundary_path(node, a, b);
    if (path.size() < 3) return -1;
    std::vector<double> along(path.size(), 0.0);
    for (std::size_t k = 1; k < path.size(); ++k) along[k] = along[k - 1] + (point(path[k]) - point(path[k - 1])).norm();
    int best = -1;
    double best_gap = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k + 1 < path.size(); ++k) {
      if (std::find(corners.begin(), corners.end(), path[k]) != corners.end()) continue;
      const double gap = std::abs(along.back() - 2.0 * along[k]);
      if (gap < best_gap) {
        best_gap = gap;
        best = path[k];
      }
    }
    return best;
  }

  /// Algorithm 7.2's refinement of one triangle: a three-split at v_q/v_r;
  /// side splits where corner angles are below the threshold (two sides
  /// around one small angle, the side between two small ones) or when P has no
  /// interior vertex.
  void plan_split(const FlintstoneNode3& node, Plan& plan) const {
    const Triple c = node.corners;
    const auto& m = plan.side_vertex;
    std::array<bool, 3> small{};
    int small_count = 0;
    for (int k = 0; k < 3; ++k) {
      small[static_cast<std::size_t>(k)] = corner_angle(c, k) < options_.angle_threshold;
      small_count += small[static_cast<std::size_t>(k)];
    }
    const auto at = [](int k) { return static_cast<std::size_t>((k + 3) % 3); };
    if (plan.split >= 0 && small_count == 0) {
      plan.three = true;
      return;
    }
    if (small_count == 1) {
      const int p = static_cast<int>(std::find(small.begin(), small.end(), true) - small.begin());
      if (m[at(p)] >= 0 && m[at(p + 2)] >= 0) {
        plan.sides[at(p)] = plan.sides[at(p + 2)] = true;
        return;
      }
    }
    for (int k = 0; k < 3; ++k)
      if (small[at(k)] && small[at(k + 1)] && m[at(k)] >= 0) {
        plan.sides[at(k)] = true;
        return;
      }
    if (plan.split >= 0) {
      plan.three = true;
      return;
    }
    for (int k = 0; k < 3; ++k)
      if (m[at(k)] >= 0) {
        plan.sides[at(k)] = true;
        return;
      }
  }

  /// Cuts and child triangles for a split at one, two or three sides
  /// (Figure 7.10); side k runs from c[k] to c[k+1] and is split at m[k].
  static void side_split(const Triple& c, const std::array<int, 3>& m, const std::array<bool, 3>& sides,
                         std::vector<Cut>& cuts, std::vector<Triple>& children) {
    const auto at = [](int k) { return static_cast<std::size_t>((k + 3) % 3); };
    const int count = static_cast<int>(std::count(sides.begin(), sides.end(), true));
    if (count == 3) {
      cuts = {{m[0], m[1]}, {m[1], m[2]}, {m[2], m[0]}};
      children = {{c[0], m[0], m[2]}, {m[0], c[1], m[1]}, {m[2], m[1], c[2]}, {m[0], m[1], m[2]}};
      return;
    }
    if (count == 2) {  // the split sides p and p+2 meet at corner p
      int p = 0;
      while (!(sides[at(p)] && sides[at(p + 2)])) ++p;
      const int m1 = m[at(p)], m2 = m[at(p + 2)];
      cuts = {{m1, m2}, {m1, c[at(p + 2)]}};
      children = {{c[at(p)], m1, m2}, {m1, c[at(p + 1)], c[at(p + 2)]}, {m1, c[at(p + 2)], m2}};
      return;
    }
    const int k = static_cast<int>(std::find(sides.begin(), sides.end(), true) - sides.begin());
    cuts = {{m[at(k)], c[at(k + 2)]}};
    children = {{c[at(k)], m[at(k)], c[at(k + 2)]}, {m[at(k)], c[at(k + 1)], c[at(k + 2)]}};
  }

  /// Cuts the node's faces along shortest edge paths (Dijkstra inside the
  /// open polyhedron) and labels the connected pieces; empty when fewer than
  /// two pieces result.
  std::vector<int> label_components(const std::vector<int>& faces,
                                    const std::vector<Cut>& cuts) {
    if (cuts.empty()) return {};
    build_adjacency(faces);
    std::unordered_set<std::uint64_t> cut_edges;
    // One Dijkstra per distinct source (a three-split cuts from v_q thrice).
    for (std::size_t first = 0; first < cuts.size();) {
      std::size_t last = first;
      while (last < cuts.size() && cuts[last].from == cuts[first].from) ++last;
      shortest_paths(cuts[first].from, {cuts.begin() + static_cast<std::ptrdiff_t>(first), cuts.begin() + static_cast<std::ptrdiff_t>(last)});
      for (std::size_t c = first; c < last; ++c)
        for (int v = local_[static_cast<std::size_t>(cuts[c].to)];
             v >= 0 && previous_[static_cast<std::size_t>(v)] >= 0; v = previous_[static_cast<std::size_t>(v)])
          cut_edges.insert(undirected_key(vertices_[static_cast<std::size_t>(v)],
                                          vertices_[static_cast<std::size_t>(previous_[static_cast<std::size_t>(v)])]));
      first = last;
    }
    const auto crossable = [&](int f, int k) {
      return !cut_edges.count(undirected_key(face_vertex(f, k), face_vertex(f, (k + 1) % 3)));
    };
    std::vector<int> labels = flood(faces, crossable);
    if (*std::max_element(labels.begin(), labels.end()) == 0) labels.clear();
    return labels;
  }

  /// Connected components of the node's faces through edges `crossable` allows.
  template <typename Crossable>
  std::vector<int> flood(const std::vector<int>& faces, const Crossable& crossable) {
    for (const int f : faces) face_label_[static_cast<std::size_t>(f)] = -1;
    int label = 0;
    std::vector<int> stack;
    for (const int seed : faces) {
      if (face_label_[static_cast<std::size_t>(seed)] >= 0) continue;
      face_label_[static_cast<std::size_t>(seed)] = label;
      stack.push_back(seed);
      while (!stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        for (int k = 0; k < 3; ++k) {
          const int g = neighbor(f, k);
          if (face_mark_[static_cast<std::size_t>(g)] != face_mark_[static_cast<std::size_t>(f)] ||
              face_label_[static_cast<std::size_t>(g)] >= 0 || !crossable(f, k))
            continue;
          face_label_[static_cast<std::size_t>(g)] = label;
          stack.push_back(g);
        }
      }
      ++label;
    }
    std::vector<int> labels;
    labels.reserve(faces.size());
    for (const int f : faces) labels.push_back(face_label_[static_cast<std::size_t>(f)]);
    return labels;
  }

  /// Fallback: breadth-first order of the faces, cut in two halves, each
  /// half's connected pieces a child.
  std::vector<int> halves(const std::vector<int>& faces) {
    for (const int f : faces) face_label_[static_cast<std::size_t>(f)] = -1;
    std::deque<int> queue{faces.front()};
    face_label_[static_cast<std::size_t>(faces.front())] = 0;
    std::size_t visited = 0;
    const std::size_t half = faces.size() / 2;
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      face_label_[static_cast<std::size_t>(f)] = visited++ < half ? 0 : 1;
      for (int k = 0; k < 3; ++k) {
        const int g = neighbor(f, k);
        if (face_mark_[static_cast<std::size_t>(g)] != face_mark_[static_cast<std::size_t>(f)] ||
            face_label_[static_cast<std::size_t>(g)] != -1)
          continue;
        face_label_[static_cast<std::size_t>(g)] = 2;  // queued
        queue.push_back(g);
      }
    }
    for (const int f : faces) face_half_[static_cast<std::size_t>(f)] = face_label_[static_cast<std::size_t>(f)];
    return flood(faces, [&](int f, int k) {
      return face_half_[static_cast<std::size_t>(f)] == face_half_[static_cast<std::size_t>(neighbor(f, k))];
    });
  }

  /// Vertex adjacency (local numbering) over the node's face edges, both
  /// directions (a boundary edge belongs to one face only).
  void build_adjacency(const std::vector<int>& faces) {
    const auto local = [&](int f, int k) { return local_[static_cast<std::size_t>(face_vertex(f, k % 3))]; };
    offsets_.assign(vertices_.size() + 1, 0);
    for (const int f : faces)
      for (int k = 0; k < 3; ++k) offsets_[static_cast<std::size_t>(local(f, k)) + 1] += 2;
    for (std::size_t k = 1; k < offsets_.size(); ++k) offsets_[k] += offsets_[k - 1];
    adjacent_.resize(static_cast<std::size_t>(offsets_.back()));
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for (const int f : faces)
      for (int k = 0; k < 3; ++k) {
        adjacent_[static_cast<std::size_t>(fill[static_cast<std::size_t>(local(f, k))]++)] = local(f, k + 1);
        adjacent_[static_cast<std::size_t>(fill[static_cast<std::size_t>(local(f, k))]++)] = local(f, k + 2);
      }
  }

  /// Shortest edge paths (Dijkstra over the node's faces) from `from` to the
  /// cuts' ends, left in previous_ (local numbering; -1 at the source and at
  /// unreached vertices).
  void shortest_paths(int from, const std::vector<Cut>& cuts) {
    distance_.assign(vertices_.size(), std::numeric_limits<double>::infinity());
    previous_.assign(vertices_.size(), -1);
    const int source = local_[static_cast<std::size_t>(from)];
    if (source < 0) return;
    std::size_t waiting = 0;
    for (const Cut& cut : cuts) waiting += local_[static_cast<std::size_t>(cut.to)] >= 0 && cut.to != from;
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    distance_[static_cast<std::size_t>(source)] = 0.0;
    queue.push({0.0, source});
    while (!queue.empty() && waiting > 0) {
      const auto [d, a] = queue.top();
      queue.pop();
      if (d > distance_[static_cast<std::size_t>(a)]) continue;
      for (const Cut& cut : cuts) waiting -= cut.to != from && local_[static_cast<std::size_t>(cut.to)] == a;
      const Eigen::Vector3d pa = point(vertices_[static_cast<std::size_t>(a)]);
      for (int e = offsets_[static_cast<std::size_t>(a)]; e < offsets_[static_cast<std::size_t>(a) + 1]; ++e) {
        const int b = adjacent_[static_cast<std::size_t>(e)];
        const double nd = d + (pa - point(vertices_[static_cast<std::size_t>(b)])).norm();
        if (nd < distance_[static_cast<std::size_t>(b)]) {
          distance_[static_cast<std::size_t>(b)] = nd;
          previous_[static_cast<std::size_t>(b)] = a;
          queue.push({nd, b});
        }
      }
    }
  }

  /// Sorts the node's face range by label and appends one child per label.
  void make_children(int id, FlintstoneNode3& node, const std::vector<int>& labels, const std::vector<Triple>& children) {
    const int count = *std::max_element(labels.begin(), labels.end()) + 1;
    std::vector<int> start(static_cast<std::size_t>(count) + 1, 0);
    for (const int l : labels) ++start[static_cast<std::size_t>(l) + 1];
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    const std::vector<int> faces = face_range(node);
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < faces.size(); ++k)
      tree_.face_order[static_cast<std::size_t>(node.first_face + fill[static_cast<std::size_t>(labels[k])]++)] = faces[k];
    node.first_child = static_cast<int>(tree_.nodes.size());
    node.child_count = count;
    for (int l = 0; l < count; ++l) {
      FlintstoneNode3 child;
      child.depth = node.depth + 1;
      child.first_face = node.first_face + start[static_cast<std::size_t>(l)];
      child.face_count = start[static_cast<std::size_t>(l) + 1] - start[static_cast<std::size_t>(l)];
      tree_.nodes.push_back(child);
      candidates_.push_back(children);
    }
    tree_.nodes[static_cast<std::size_t>(id)] = node;
  }

  FlintstoneTree3& tree_;
  const FlintstoneOptions3& options_;
  const Eigen::MatrixX3d& V_;
  const Eigen::MatrixX3i& F_;
  std::vector<int> neighbor_;
  std::vector<int> face_mark_, face_label_, face_half_, local_, boundary_mark_, next_;
  std::vector<char> eligible_;
  std::vector<int> vertices_;
  std::vector<std::vector<Triple>> candidates_;
  std::vector<int> offsets_, adjacent_, previous_;
  std::vector<double> distance_;
};

}  // namespace

std::vector<int> FlintstoneTree3::reachable() const {
  std::vector<int> ids{0};
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const FlintstoneNode3& node = nodes[static_cast<std::size_t>(ids[k])];
    for (int c = 0; c < node.child_count; ++c) ids.push_back(node.first_child + c);
  }
  return ids;
}

int FlintstoneTree3::levels() const {
  int deepest = 0;
  for (const int id : reachable()) deepest = std::max(deepest, nodes[static_cast<std::size_t>(id)].depth);
  return deepest;
}

std::size_t FlintstoneTree3::storage_bytes() const {
  std::size_t boundary_edges = 0;
  const std::vector<int> ids = reachable();
  for (const int id : ids) boundary_edges += static_cast<std::size_t>(nodes[static_cast<std::size_t>(id)].boundary_count);
  return ids.size() * sizeof(FlintstoneNode3) + face_order.size() * sizeof(int) +
         boundary_edges * sizeof(std::array<int, 2>);
}

FlintstoneTree3 flintstone_tree(const TriangleMesh& mesh, const FlintstoneOptions3& options) {
  if (mesh.face_count() == 0) throw InvalidInput("flintstone tree: the mesh has no faces");
  require_ball_range<3>(mesh.vertices.positions, "mesh");
  // The root's three cut paths (§7.3.2) split one closed surface in two:
  // with several parts, or parts sharing only a vertex, they cannot, and the
  // refinement would run past the faces it was given. Open or non-manifold
  // edges are left to face_neighbors, which names one.
  const MeshTopology topology = mesh_topology(mesh);
  if (topology.boundary_edges == 0 && topology.non_manifold_edges == 0) {
    if (topology.components > 1)
      throw TopologyError("flintstone tree: the mesh has " + std::to_string(topology.components) +
                          " separate parts; a flintstone tree (§7.3) covers one closed surface: split the mesh and "
                          "build one tree per part");
    if (topology.non_manifold_vertices > 0)
      throw TopologyError("flintstone tree: " + std::to_string(topology.non_manifold_vertices) +
                          (topology.non_manifold_vertices == 1 ? " vertex joins" : " vertices join") +
                          " several fans of faces (the surface pinches there); a flintstone tree (§7.3) needs a "
                          "closed 2-manifold");
  }
  FlintstoneTree3 tree;
  tree.vertices = mesh.vertices.positions;
  tree.faces = mesh.faces;
  tree.options = options;
  Builder(tree, tree.options).run();
  return tree;
}

int insert_vertex(FlintstoneTree3& tree, int face, const Eigen::Vector3d& point) {
  const int face_count = static_cast<int>(tree.faces.rows());
  if (face < 0 || face >= face_count)
    throw InvalidInput("insert_vertex: face " + std::to_string(face) + " outside [0, " + std::to_string(face_count) + ")");
  // The face becomes three around the new vertex; the two new faces follow it
  // in face_order, inside every range that holds it.
  const int v = static_cast<int>(tree.vertices.rows());
  tree.vertices.conservativeResize(v + 1, 3);
  tree.vertices.row(v) = point.transpose();
  const Eigen::RowVector3i old = tree.faces.row(face);
  tree.faces.conservativeResize(face_count + 2, 3);
  tree.faces.row(face) << old(0), old(1), v;
  tree.faces.row(face_count) << old(1), old(2), v;
  tree.faces.row(face_count + 1) << old(2), old(0), v;
  const int at = static_cast<int>(std::find(tree.face_order.begin(), tree.face_order.end(), face) - tree.face_order.begin());
  tree.face_order.insert(tree.face_order.begin() + at + 1, {face_count, face_count + 1});
  for (FlintstoneNode3& node : tree.nodes) {
    if (node.first_face > at) node.first_face += 2;
    else if (node.first_face + node.face_count > at) node.face_count += 2;
  }
  // Down the path to the face, to the first volume that misses the vertex.
  int id = 0;
  while (true) {
    const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(id)];
    const bool holds = node.stone.contains(point) && node.bound.contains(point) && node.box.contains(point);
    if (!holds || node.leaf()) break;
    for (int c = 0; c < node.child_count; ++c) {
      const FlintstoneNode3& child = tree.nodes[static_cast<std::size_t>(node.first_child + c)];
      if (child.first_face <= at && at < child.first_face + child.face_count) id = node.first_child + c;
    }
  }
  if (id == 0) {  // outside the root ball: a new tree
    tree = flintstone_tree(TriangleMesh{PointCloud{tree.vertices, {}, {}, 3}, tree.faces}, tree.options);
  } else {
    Builder(tree, tree.options).rebuild(id);
  }
  return tree.nodes[static_cast<std::size_t>(id)].face_count;
}

}  // namespace scanstation
