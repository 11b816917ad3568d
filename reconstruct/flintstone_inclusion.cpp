#include "reconstruct/flintstone_inclusion.h"

#include "core/errors.h"
#include "core/predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace scanstation {

namespace {

enum class Crossing { none, once, on_boundary };

/// Does the ray from x along +x cross segment a b? Half-open in y (an end
/// point exactly at x's height counts only for the edge going up from it),
/// decided by an exact orientation.
Crossing ray_crossing(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& x) {
  const int o = orientation(a, b, x);
  if (o == 0 && x.x() >= std::min(a.x(), b.x()) && x.x() <= std::max(a.x(), b.x()) &&
      x.y() >= std::min(a.y(), b.y()) && x.y() <= std::max(a.y(), b.y()))
    return Crossing::on_boundary;
  if ((a.y() > x.y()) == (b.y() > x.y())) return Crossing::none;
  return (b.y() > x.y() ? o > 0 : o < 0) ? Crossing::once : Crossing::none;
}

}  // namespace

bool inside(const FlintstoneTree2& tree, const Eigen::Vector2d& x, InclusionStats* stats) {
  InclusionStats local;
  InclusionStats& count = stats ? *stats : local;
  ++count.flintstone_tests;
  if (!tree.root.contains(x)) return false;  // outside the bounding disc
  bool odd = false;
  std::vector<Chain2> stack;
  const auto tops = tree.top_chains();
  stack.assign(tops.begin(), tops.end());
  while (!stack.empty()) {
    const Chain2 chain = stack.back();
    stack.pop_back();
    const Eigen::Vector2d a = tree.point(chain.p), b = tree.point(chain.s);
    if (chain.node >= 0) {
      const FlintstoneNode2& node = tree.nodes[static_cast<std::size_t>(chain.node)];
      ++count.flintstone_tests;
      // Lemma 6.1: outside F(v_p … v_s) the edge v_p v_s answers for the chain
      // (it lies in both balls, which are convex; a union flintstone, only
      // possible for degenerate input, is always refined).
      if (node.stone.is_union || node.stone.contains(x) || orientation(a, b, x) == 0) {
        const auto children = tree.children(node);
        stack.insert(stack.end(), children.begin(), children.end());
        continue;
      }
      ++count.replacements;
    }
    ++count.crossing_tests;
    const Crossing crossing = ray_crossing(a, b, x);
    if (crossing == Crossing::on_boundary) return true;
    if (crossing == Crossing::once) odd = !odd;
  }
  return odd;
}

bool inside_brute_force(const Eigen::MatrixX2d& V, const Eigen::Vector2d& x) {
  bool odd = false;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Crossing crossing = ray_crossing(V.row(i).transpose(), V.row((i + 1) % V.rows()).transpose(), x);
    if (crossing == Crossing::on_boundary) return true;
    if (crossing == Crossing::once) odd = !odd;
  }
  return odd;
}

namespace {

enum class Crossing3 { none, once, on_boundary, degenerate };

bool collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  return CGAL::collinear(Point(a.x(), a.y(), a.z()), Point(b.x(), b.y(), b.z()), Point(c.x(), c.y(), c.z()));
}

/// Does segment x q cross triangle a b c? Exact: orientation signs only.
/// `degenerate` when the answer would depend on how a touch is counted.
Crossing3 segment_crossing(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           const Eigen::Vector3d& x, const Eigen::Vector3d& q) {
  const int sx = orientation(a, b, c, x), sq = orientation(a, b, c, q);
  if (sx == 0 && sq == 0 && collinear(a, b, c)) return Crossing3::none;  // a flat face: its edges are its neighbours'
  if (sx == 0) {
    // x in the triangle's plane: on the triangle, or touching the plane only at x.
    const Eigen::Vector3d lifted = a + (b - a).cross(c - a);  // a point off the plane
    if (orientation(a, b, c, lifted) == 0) return Crossing3::degenerate;
    const int u = orientation(a, b, lifted, x), v = orientation(b, c, lifted, x), w = orientation(c, a, lifted, x);
    if ((u >= 0 && v >= 0 && w >= 0) || (u <= 0 && v <= 0 && w <= 0)) return Crossing3::on_boundary;
    return sq == 0 ? Crossing3::degenerate : Crossing3::none;
  }
  if (sq == 0) return Crossing3::degenerate;
  if (sx == sq) return Crossing3::none;
  const int e1 = orientation(x, q, a, b), e2 = orientation(x, q, b, c), e3 = orientation(x, q, c, a);
  if ((e1 > 0 && e2 > 0 && e3 > 0) || (e1 < 0 && e2 < 0 && e3 < 0)) return Crossing3::once;
  if ((std::min({e1, e2, e3}) < 0 && std::max({e1, e2, e3}) > 0)) return Crossing3::none;
  return Crossing3::degenerate;  // through an edge or a vertex
}

/// The k-th ray direction: a golden-ratio spiral over the sphere, far from
/// axis-aligned.
Eigen::Vector3d ray_direction(int k) {
  const double spread = 0.3183 + 0.6180339887498949 * k;
  const double z = 2.0 * (spread - std::floor(spread)) - 1.0;
  const double angle = 0.4127 + 2.39996322972865332 * k;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(angle), r * std::sin(angle), z};
}

/// The far end of the ray from x: beyond the ball (center, radius), in the
/// k-th direction of the spiral.
Eigen::Vector3d far_point(const Eigen::Vector3d& x, int attempt, const Eigen::Vector3d& center, double radius) {
  const double length = 2.0 * ((x - center).norm() + radius);
  return x + (length > 0.0 ? length : 1.0) * ray_direction(attempt);
}

/// For the tree: a ray leaving the root ball about radially (perturbed by the
/// spiral), the shortest way out, so it meets few flintstones.
Eigen::Vector3d outward_point(const Eigen::Vector3d& x, int attempt, const Eigen::Vector3d& center, double radius) {
  const Eigen::Vector3d radial = x - center;
  const double distance = radial.norm();
  if (!(distance > 1e-3 * radius)) return far_point(x, attempt, center, radius);
  const Eigen::Vector3d direction = (radial / distance + 0.3 * ray_direction(attempt)).normalized();
  // |q − center| ≥ length − distance ≥ 1.5·radius: q lies outside the root ball.
  return x + (1.5 * radius + 2.0 * distance) * direction;
}

constexpr int max_attempts = 256;

/// Lemma 6.1 pays off while the fan is short; a long fan costs more than
/// refining (the children are usually missed by the ray).
constexpr int fan_limit = 4;

/// The ray of one query as a segment x → x + length·direction, with the
/// direction normalised once so each volume test below costs a few flops.
/// A zero direction component gets a huge finite inverse, so the slab test
/// needs no special case and never meets 0·∞.
struct QuerySegment {
  Eigen::Vector3d x, q;
  Eigen::Array3d origin, direction, inverse;
  double length;
  QuerySegment(const Eigen::Vector3d& from, const Eigen::Vector3d& to) : x(from), q(to), origin(from.array()) {
    const Eigen::Vector3d along = to - from;
    length = along.norm();
    direction = length > 0.0 ? Eigen::Array3d(along.array() / length) : Eigen::Array3d::Zero();
    inverse = direction.unaryExpr([](double d) { return d == 0.0 ? 1e300 : 1.0 / d; });
  }
};

/// A volume against the query: whether x lies outside it and whether the
/// segment misses it. Both stay on the safe side: a missed volume never
/// holds x, and a segment that meets the faces inside is never called missing.
struct VolumeTest {
  bool x_outside, segment_misses;
};

/// A ball, with the relative slack of segment_misses.
inline VolumeTest test_ball(const SignedBall<3>& ball, const QuerySegment& s) {
  const Eigen::Array3d w = ball.center.array() - s.origin;
  const double r2 = ball.radius * ball.radius;
  const double t = std::clamp((w * s.direction).sum(), 0.0, s.length);
  return {w.square().sum() > r2, (w - t * s.direction).square().sum() > r2 * (1.0 + 1e-9)};
}

/// A box (slab test). The box is widened by a relative slack when built, far
/// more than the rounding here.
inline VolumeTest test_box(const Eigen::AlignedBox3d& box, const QuerySegment& s) {
  const Eigen::Array3d lo = box.min().array() - s.origin, hi = box.max().array() - s.origin;
  const Eigen::Array3d a = lo * s.inverse, b = hi * s.inverse;
  const double enter = std::max(a.min(b).maxCoeff(), 0.0), leave = std::min(a.max(b).minCoeff(), s.length);
  return {(lo > 0.0).any() || (hi < 0.0).any(), enter > leave};
}

/// One ray through the tree: 0/1 parity, 2 on the boundary, -1 degenerate.
int tree_parity(const FlintstoneTree3& tree, const QuerySegment& s, InclusionStats& count) {
  const auto point = [&](int v) { return Eigen::Vector3d(tree.vertices.row(v).transpose()); };
  bool odd = false;
  const auto add = [&](Crossing3 crossing) {
    if (crossing == Crossing3::once) odd = !odd;
    return crossing == Crossing3::on_boundary ? 2 : crossing == Crossing3::degenerate ? -1 : 0;
  };
  thread_local std::vector<int> stack;  // reused: no allocation per query
  stack.assign(1, 0);
  while (!stack.empty()) {
    const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(stack.back())];
    const bool root = stack.back() == 0;
    stack.pop_back();
    const VolumeTest box = test_box(node.box, s);
    if (!root && box.segment_misses) continue;  // the faces lie in the box; x is not on them
    if (node.leaf()) {
      const int f = tree.face_order[static_cast<std::size_t>(node.first_face)];
      ++count.crossing_tests;
      const int r = add(segment_crossing(point(tree.faces(f, 0)), point(tree.faces(f, 1)), point(tree.faces(f, 2)), s.x, s.q));
      if (r != 0) return r;
      continue;
    }
    ++count.flintstone_tests;
    // The localizing volume is F(P) ∩ box; when F(P) is a union only the box
    // is used (the faces and the fan need not lie in a union of balls). A
    // segment that misses the volume misses the node's faces, and x then lies
    // outside the volume as well. (The node's bound ball adds nothing here
    // once the box is tested: measured, it prunes < 1% of the visits.)
    bool outside = box.x_outside;
    if (!root && !node.stone.is_union) {
      const VolumeTest first = test_ball(node.stone.first, s);
      if (first.segment_misses) continue;
      const VolumeTest second = test_ball(node.stone.second, s);
      if (second.segment_misses) continue;
      outside = outside || first.x_outside || second.x_outside;
    }
    if (root || !outside || node.boundary_count > fan_limit) {
      for (int c = 0; c < node.child_count; ++c) stack.push_back(node.first_child + c);
      continue;
    }
    // Lemma 6.1: the fan over the boundary answers for the node's faces.
    ++count.replacements;
    const Eigen::Vector3d apex = point(node.corners[0]);
    for (int e = 0; e < node.boundary_count; ++e) {
      const auto [a, b] = tree.boundary[static_cast<std::size_t>(node.first_boundary + e)];
      if (a == node.corners[0] || b == node.corners[0]) continue;  // a flat fan triangle
      ++count.crossing_tests;
      if (add(segment_crossing(apex, point(a), point(b), s.x, s.q)) != 0) return -1;  // never on a fan: retry
    }
  }
  return odd ? 1 : 0;
}

}  // namespace

bool inside(const FlintstoneTree3& tree, const Eigen::Vector3d& x, InclusionStats* stats) {
  InclusionStats local;
  InclusionStats& count = stats ? *stats : local;
  const Flintstone<3>& root = tree.root().stone;
  ++count.flintstone_tests;
  if (!root.contains(x)) return false;
  for (int attempt = 0; attempt < max_attempts; ++attempt) {
    const int r = tree_parity(tree, QuerySegment(x, outward_point(x, attempt, root.first.center, root.first.radius)), count);
    if (r >= 0) return r != 0;
  }
  return inside_brute_force(tree.vertices, tree.faces, x);
}

bool inside_brute_force(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::Vector3d& x) {
  const Eigen::Vector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  for (int attempt = 0; attempt < max_attempts; ++attempt) {
    const Eigen::Vector3d q = far_point(x, attempt, 0.5 * (lo + hi), 0.5 * (hi - lo).norm());
    bool odd = false, retry = false;
    for (Eigen::Index f = 0; f < F.rows() && !retry; ++f) {
      const Crossing3 crossing = segment_crossing(V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(),
                                                  V.row(F(f, 2)).transpose(), x, q);
      if (crossing == Crossing3::on_boundary) return true;
      retry = crossing == Crossing3::degenerate;
      odd ^= crossing == Crossing3::once;
    }
    if (!retry) return odd;
  }
  throw SolverError("point inclusion: no non-degenerate ray after " + std::to_string(max_attempts) + " directions");
}

}  // namespace scanstation
