#include "reconstruct/flintstone_inclusion.h"

#include "core/errors.h"
#include "core/predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <limits>
#include <optional>

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

/// orientation(x, q, a, b) for any segment x q.
struct EdgeSide {
  const Eigen::Vector3d &x, &q;
  int operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const { return orientation(x, q, a, b); }
};

/// Does segment x q cross triangle a b c? Exact: orientation signs only.
/// `degenerate` when the answer would depend on how a touch is counted.
/// `side(a, b)` is orientation(x, q, a, b) (cheaper for an axis-aligned x q).
/// The sides of the line x q against the three edges come first: the segments
/// reaching a leaf mostly pass beside its triangle, and strictly mixed signs
/// prove that the whole line misses the closed triangle (its projection along
/// x q lies outside the projected triangle), so neither plane test is needed.
template <class Side>
Crossing3 segment_crossing(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           const Eigen::Vector3d& x, const Eigen::Vector3d& q, const Side& side) {
  const int e1 = side(a, b), e2 = side(b, c);
  if (e1 * e2 < 0) return Crossing3::none;
  const int e3 = side(c, a);
  if (e1 * e3 < 0 || e2 * e3 < 0) return Crossing3::none;
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
  if ((e1 > 0 && e2 > 0 && e3 > 0) || (e1 < 0 && e2 < 0 && e3 < 0)) return Crossing3::once;
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

/// The float at or above d (at or below for round_down): the packed boxes are
/// floats rounded outwards, so a float box holds the exact one and a miss
/// decided in floats is a miss of the exact box.
inline float round_up(double d) {
  constexpr double largest = std::numeric_limits<float>::max();
  const float f = static_cast<float>(std::clamp(d, -largest, largest));  // in range: a defined conversion
  if (f >= d) return f;
  if (d > largest) return std::numeric_limits<float>::infinity();
  if (f == 0.0f) return std::numeric_limits<float>::denorm_min();
  // One float step up: the magnitude's bits grow for a positive f, shrink for a negative one.
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(f) + (f > 0.0f ? 1u : std::uint32_t(-1)));
}

inline float round_down(double d) { return -round_up(-d); }

/// Four floats in one SIMD register (GCC/Clang vector extension: SSE on
/// x86-64, NEON on ARM), and the lane-wise comparison masks.
using Float4 = float __attribute__((vector_size(16)));
using Mask4 = std::int32_t __attribute__((vector_size(16)));

/// The first ray: along the axis towards the nearest face of the box of all
/// vertices, ending beyond it — the shortest segment that leaves every face
/// behind, and an axis-aligned one, so it meets the fewest node boxes, a box
/// test is the overlap of two boxes (comparisons only, exact) and an edge
/// test is a 2D orientation across the axis (CGAL's Side_of_triangle_mesh
/// casts a vertical ray for the same reasons).
struct AxisSegment {
  Eigen::Vector3d x, q;
  Eigen::Array3d lo, hi;  ///< the segment's own box
  /// hi, −lo rounded up, as two Float4 matching a node's first and last 16
  /// bytes (bounds 0–3; bounds 4–5 and two lanes of +∞ opposite skip and
  /// first_triangle, which never exceed +∞): a node misses when one of its
  /// bounds exceeds its match.
  Float4 low4, high4;
  int axis = 0, u = 1, v = 2;  ///< the ray's axis and the two across it (a right-handed u, v, axis)
  int sign = 1;                ///< the sign of q − x along the axis
  // For test_ball:
  Eigen::Array3d origin, direction = Eigen::Array3d::Zero();
  double length = 0.0;
  AxisSegment(const Eigen::Vector3d& point, const Eigen::AlignedBox3d& box) : x(point), q(point), origin(point.array()) {
    double shortest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const double below = x[k] - box.min()[k], above = box.max()[k] - x[k];
      if (below < shortest) shortest = below, axis = k, sign = -1;
      if (above < shortest) shortest = above, axis = k, sign = 1;
    }
    u = axis == 2 ? 0 : axis + 1;
    v = axis == 0 ? 2 : axis - 1;
    // Strictly beyond the box, whatever the rounding at large coordinates.
    const double margin = 1e-3 * box.sizes().maxCoeff() + 1e-6 * std::abs(x[axis]);
    q[axis] = sign < 0 ? box.min()[axis] - margin : box.max()[axis] + margin;
    lo = x.array().min(q.array());
    hi = x.array().max(q.array());
    // The far end lies beyond every box: ±∞ there, so only x is rounded.
    constexpr float infinity = std::numeric_limits<float>::infinity();
    std::array<float, 6> b;
    for (int k = 0; k < 3; ++k) {
      b[static_cast<std::size_t>(k)] = k == axis && sign > 0 ? infinity : round_up(x[k]);
      b[static_cast<std::size_t>(k + 3)] = k == axis && sign < 0 ? infinity : round_up(-x[k]);
    }
    low4 = Float4{b[0], b[1], b[2], b[3]};
    high4 = Float4{b[4], b[5], infinity, infinity};
    length = hi[axis] - lo[axis];
    direction[axis] = sign;
  }
  /// orientation(x, q, a, b) = sign(q − x along the axis) · the orientation
  /// of x, a, b projected across the axis (expand the determinant along q − x).
  /// CGAL's filtered predicate called here rather than through
  /// core/predicates.h, so it is inlined into the leaf test (the hottest
  /// exact test: measured, the call cost as much as the filter).
  int operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_2;
    return sign * static_cast<int>(CGAL::orientation(Point(x[u], x[v]), Point(a[u], a[v]), Point(b[u], b[v])));
  }
};

/// The later rays (after a degenerate one) as a segment x → x + length·direction,
/// with the direction normalised once so each volume test below costs a few
/// flops. A zero direction component gets a huge finite inverse, so the slab
/// test needs no special case and never meets 0·∞.
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
  int operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const { return orientation(x, q, a, b); }
};

constexpr int max_attempts = 256;

/// Lemma 6.1 pays off while the fan is short; a long fan costs more than
/// refining (the children are usually missed by the ray).
constexpr int fan_limit = 4;

/// A volume against the query: whether x lies outside it and whether the
/// segment misses it. Both stay on the safe side: a missed volume never
/// holds x, and a segment that meets the faces inside is never called missing.
struct VolumeTest {
  bool x_outside, segment_misses;
};

/// A ball (center c, radius r), with the relative slack of segment_misses.
template <class Segment>
inline VolumeTest test_ball(const Eigen::Vector3d& c, double r, const Segment& s) {
  const Eigen::Array3d w = c.array() - s.origin;
  const double r2 = r * r;
  const double t = std::clamp((w * s.direction).sum(), 0.0, s.length);
  return {w.square().sum() > r2, (w - t * s.direction).square().sum() > r2 * (1.0 + 1e-9)};
}

/// Whether the segment misses a box (slab test). The box is widened by a
/// relative slack when built, far more than the rounding here.
inline bool misses(const Eigen::AlignedBox3d& box, const QuerySegment& s) {
  const Eigen::Array3d a = (box.min().array() - s.origin) * s.inverse, b = (box.max().array() - s.origin) * s.inverse;
  return std::max(a.min(b).maxCoeff(), 0.0) > std::min(a.max(b).minCoeff(), s.length);
}

/// Whether an axis-aligned segment misses a box: its own box does. Exact,
/// and without branches.
inline bool misses(const Eigen::AlignedBox3d& box, const AxisSegment& s) {
  return ((box.min().array() > s.hi) || (box.max().array() < s.lo)).any();
}

/// Whether an axis-aligned segment misses a node's float box: all six
/// comparisons at once, two 4-wide compares and no branch (a node is 32
/// bytes: six floats, skip, first_triangle).
static_assert(sizeof(FlintstoneInclusion3::Node) == 32 && offsetof(FlintstoneInclusion3::Node, skip) == 24);
inline bool misses(const FlintstoneInclusion3::Node& node, const AxisSegment& s) {
  Float4 first, last;
  std::memcpy(&first, &node, sizeof first);
  std::memcpy(&last, reinterpret_cast<const char*>(&node) + sizeof first, sizeof last);
  const Mask4 over = (first > s.low4) | (last > s.high4);
#if defined(__SSE__)
  return __builtin_ia32_movmskps(reinterpret_cast<Float4>(over)) != 0;  // one instruction
#else
  std::uint64_t halves[2];
  std::memcpy(halves, &over, sizeof halves);
  return (halves[0] | halves[1]) != 0;
#endif
}

inline bool outside(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& x) {
  return ((box.min().array() > x.array()) || (box.max().array() < x.array())).any();
}

/// Crossing parity of one ray: each call returns 0 to go on, 2 when x lies on
/// a face, -1 when the ray is degenerate.
template <class Segment>
class Parity {
 public:
  Parity(const Segment& s, InclusionStats& count) : s_(s), count_(count) {}
  /// A face of the mesh.
  int face(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    ++count_.crossing_tests;
    const Crossing3 crossing = segment_crossing(a, b, c, s_.x, s_.q, s_);
    if (crossing == Crossing3::once) odd_ = !odd_;
    return crossing == Crossing3::on_boundary ? 2 : crossing == Crossing3::degenerate ? -1 : 0;
  }
  /// A fan triangle (Lemma 6.1): x lies outside the fan's volume, so a touch
  /// only means that the ray is degenerate.
  int fan(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return face(a, b, c) != 0 ? -1 : 0;
  }
  int result() const { return odd_ ? 1 : 0; }

 private:
  const Segment& s_;
  InclusionStats& count_;
  bool odd_ = false;
};

/// One ray through the tree: 0/1 parity, 2 on the boundary, -1 degenerate.
template <class Segment>
int tree_parity(const FlintstoneTree3& tree, const Segment& s, InclusionStats& count) {
  const auto point = [&](int v) { return Eigen::Vector3d(tree.vertices.row(v).transpose()); };
  Parity<Segment> parity(s, count);
  thread_local std::vector<int> stack;  // reused: no allocation per query
  stack.assign(1, 0);
  while (!stack.empty()) {
    const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(stack.back())];
    const bool root = stack.back() == 0;
    stack.pop_back();
    if (!root && misses(node.box, s)) continue;  // the faces lie in the box; x is not on them
    if (node.leaf()) {
      const int f = tree.face_order[static_cast<std::size_t>(node.first_face)];
      const int r = parity.face(point(tree.faces(f, 0)), point(tree.faces(f, 1)), point(tree.faces(f, 2)));
      if (r != 0) return r;
      continue;
    }
    ++count.flintstone_tests;
    // The localizing volume is F(P) ∩ box; when F(P) is a union only the box
    // is used (the faces and the fan need not lie in a union of balls). A
    // segment that misses the volume misses the node's faces, and x then lies
    // outside the volume as well. (The node's bound ball adds nothing here
    // once the box is tested: measured, it prunes < 1% of the visits.)
    bool x_outside = outside(node.box, s.x);
    if (!root && !node.stone.is_union) {
      const VolumeTest first = test_ball(node.stone.first.center, node.stone.first.radius, s);
      if (first.segment_misses) continue;
      const VolumeTest second = test_ball(node.stone.second.center, node.stone.second.radius, s);
      if (second.segment_misses) continue;
      x_outside = x_outside || first.x_outside || second.x_outside;
    }
    if (root || !x_outside || node.boundary_count > fan_limit) {
      for (int c = 0; c < node.child_count; ++c) stack.push_back(node.first_child + c);
      continue;
    }
    // Lemma 6.1: the fan over the boundary answers for the node's faces.
    ++count.replacements;
    const Eigen::Vector3d apex = point(node.corners[0]);
    for (int e = 0; e < node.boundary_count; ++e) {
      const auto [a, b] = tree.boundary[static_cast<std::size_t>(node.first_boundary + e)];
      if (a == node.corners[0] || b == node.corners[0]) continue;  // a flat fan triangle
      if (parity.fan(apex, point(a), point(b)) != 0) return -1;  // retry
    }
  }
  return parity.result();
}

/// One ray through the packed index: the volumes and Lemma 6.1 replacements
/// of tree_parity in one forward sweep over the depth-first layout — a node
/// that is missed or replaced jumps to its `skip`, any other node steps into
/// its subtree — so no stack. The box alone prunes; the lens F(P) is tested
/// only where it can allow a replacement (measured: testing it on every
/// visit costs more than it prunes). `misses(node)` is the box test.
template <class Segment, class Misses>
int sweep_parity(const FlintstoneInclusion3& index, const Segment& s, const Misses& misses, InclusionStats& count) {
  Parity<Segment> parity(s, count);
  const int end = static_cast<int>(index.nodes.size());
  for (int k = 1; k < end;) {  // nodes[0] is the root: never missed, never replaced
    const FlintstoneInclusion3::Node& node = index.nodes[static_cast<std::size_t>(k)];
    if (misses(node)) {
      k = node.skip;
      continue;
    }
    if (node.leaf(k)) {
      const auto& t = index.triangles[static_cast<std::size_t>(node.first_triangle)];
      const int r = parity.face(t[0], t[1], t[2]);
      if (r != 0) return r;
      ++k;
      continue;
    }
    // A short fan (its triangles end where the first child's begin): can x
    // use it? Only here is a flintstone tested (sorting nodes have no fan).
    const int fan_end = index.nodes[static_cast<std::size_t>(k) + 1].first_triangle;
    bool x_outside = false;
    if (fan_end > node.first_triangle) {
      ++count.flintstone_tests;
      x_outside = outside(node.box(), s.x);
      const int lens_id = index.lens_of[static_cast<std::size_t>(k)];
      if (!x_outside && lens_id >= 0) {  // F(P) ∩ box
        const FlintstoneInclusion3::Lens& lens = index.lenses[static_cast<std::size_t>(lens_id)];
        const VolumeTest first = test_ball(lens.first_center, lens.first_radius, s);
        const VolumeTest second = test_ball(lens.second_center, lens.second_radius, s);
        if (first.segment_misses || second.segment_misses) {
          k = node.skip;
          continue;
        }
        x_outside = first.x_outside || second.x_outside;
      }
    }
    if (!x_outside) {
      ++k;
      continue;
    }
    // Lemma 6.1: the fan over the boundary answers for the node's faces.
    ++count.replacements;
    for (int t = node.first_triangle; t < fan_end; ++t) {
      const auto& triangle = index.triangles[static_cast<std::size_t>(t)];
      if (parity.fan(triangle[0], triangle[1], triangle[2]) != 0) return -1;
    }
    k = node.skip;
  }
  return parity.result();
}

int index_parity(const FlintstoneInclusion3& index, const AxisSegment& s, InclusionStats& count) {
  return sweep_parity(index, s, [&](const FlintstoneInclusion3::Node& node) { return misses(node, s); }, count);
}

int index_parity(const FlintstoneInclusion3& index, const QuerySegment& s, InclusionStats& count) {
  return sweep_parity(index, s, [&](const FlintstoneInclusion3::Node& node) { return misses(node.box(), s); }, count);
}

/// Rays until one is not degenerate: the axis ray first, then rays leaving
/// the root ball about radially (perturbed by the spiral), the shortest way
/// out, so they meet few flintstones. `parity(segment)` is 0/1, 2 on the
/// boundary, -1 degenerate.
template <class RayParity>
std::optional<bool> first_answer(const Eigen::Vector3d& x, const Eigen::AlignedBox3d& box, const SignedBall<3>& ball,
                                 const RayParity& parity) {
  const int r = parity(AxisSegment(x, box));
  if (r >= 0) return r != 0;
  for (int attempt = 0; attempt < max_attempts; ++attempt) {
    const int r = parity(QuerySegment(x, outward_point(x, attempt, ball.center, ball.radius)));
    if (r >= 0) return r != 0;
  }
  return std::nullopt;
}

}  // namespace

bool inside(const FlintstoneTree3& tree, const Eigen::Vector3d& x, InclusionStats* stats) {
  InclusionStats local;
  InclusionStats& count = stats ? *stats : local;
  const FlintstoneNode3& root = tree.root();
  ++count.flintstone_tests;
  if (!root.stone.contains(x) || outside(root.box, x)) return false;
  const auto answer = first_answer(x, root.box, root.stone.first,
                                   [&](const auto& segment) { return tree_parity(tree, segment, count); });
  return answer ? *answer : inside_brute_force(tree.vertices, tree.faces, x);
}

namespace {

/// Chain collapsing: an inner node is kept only when its box's surface area
/// is below this share of its packed parent's (a ray across the parent
/// meets the child with a chance about the ratio of their areas).
constexpr double collapse_ratio = 0.8;

bool worth_a_visit(const Eigen::AlignedBox3d& child, const Eigen::AlignedBox3d& parent) {
  const auto area = [](const Eigen::AlignedBox3d& box) {
    const Eigen::Vector3d d = box.sizes();
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  };
  return area(child) < collapse_ratio * area(parent);
}

/// Packs a tree depth first: each packed node's children are the tree
/// node's children with chains that prune little collapsed into their own
/// children, and many children are sorted under boxes of their own.
class Packer {
 public:
  Packer(const FlintstoneTree3& tree, FlintstoneInclusion3& index) : tree_(tree), index_(index) {}

  void add(int id) {
    const FlintstoneNode3& node = tree_.nodes[static_cast<std::size_t>(id)];
    const int k = open(node.box);
    if (node.leaf()) {
      const int f = tree_.face_order[static_cast<std::size_t>(node.first_face)];
      index_.triangles.push_back({point(tree_.faces(f, 0)), point(tree_.faces(f, 1)), point(tree_.faces(f, 2))});
    } else if (id != 0 && node.boundary_count <= fan_limit) {
      for (int e = 0; e < node.boundary_count; ++e) {
        const auto [a, b] = tree_.boundary[static_cast<std::size_t>(node.first_boundary + e)];
        if (a == node.corners[0] || b == node.corners[0]) continue;  // a flat fan triangle
        index_.triangles.push_back({point(node.corners[0]), point(a), point(b)});
      }
      if (!node.stone.is_union) {
        index_.lens_of.back() = static_cast<int>(index_.lenses.size());
        index_.lenses.push_back(
            {node.stone.first.center, node.stone.second.center, node.stone.first.radius, node.stone.second.radius});
      }
    }
    std::vector<int> children;
    expand_.assign(1, id);
    while (!expand_.empty()) {
      const FlintstoneNode3& from = tree_.nodes[static_cast<std::size_t>(expand_.back())];
      expand_.pop_back();
      for (int c = from.first_child + from.child_count - 1; c >= from.first_child; --c) {
        const FlintstoneNode3& child = tree_.nodes[static_cast<std::size_t>(c)];
        if (!child.leaf() && !worth_a_visit(child.box, node.box)) expand_.push_back(c);
        else children.push_back(c);
      }
    }
    place(children);
    close(k);
  }

 private:
  /// Many children (the collapsed top of the tree) would each cost a box
  /// test on every visit: above `wide` they are sorted along the longest
  /// axis of their joint box and split in halves under a node of that box
  /// (no fan: always refined, so Lemma 6.1 is still decided by the tree's
  /// own nodes below it).
  static constexpr std::size_t wide = 4;

  void place(std::vector<int> ids) {
    if (ids.size() <= wide) {
      for (const int c : ids) add(c);
      return;
    }
    Eigen::AlignedBox3d joint;
    for (const int c : ids) joint.extend(tree_.nodes[static_cast<std::size_t>(c)].box);
    Eigen::Index axis = 0;
    joint.sizes().maxCoeff(&axis);
    std::sort(ids.begin(), ids.end(), [&](int a, int b) {
      return tree_.nodes[static_cast<std::size_t>(a)].box.center()[axis] < tree_.nodes[static_cast<std::size_t>(b)].box.center()[axis];
    });
    const auto middle = ids.begin() + static_cast<std::ptrdiff_t>(ids.size() / 2);
    for (std::vector<int> half : {std::vector<int>(ids.begin(), middle), std::vector<int>(middle, ids.end())}) {
      if (half.size() == 1) {
        add(half.front());
        continue;
      }
      Eigen::AlignedBox3d box;
      for (const int c : half) box.extend(tree_.nodes[static_cast<std::size_t>(c)].box);
      const int k = open(box);
      index_.lens_of.back() = FlintstoneInclusion3::sorting_node;
      place(half);
      close(k);
    }
  }

  int open(const Eigen::AlignedBox3d& box) {
    FlintstoneInclusion3::Node packed;
    for (int i = 0; i < 3; ++i) {
      packed.bounds[static_cast<std::size_t>(i)] = round_down(box.min()[i]);
      packed.bounds[static_cast<std::size_t>(i + 3)] = round_down(-box.max()[i]);
    }
    packed.first_triangle = static_cast<int>(index_.triangles.size());
    index_.nodes.push_back(packed);
    index_.lens_of.push_back(-1);
    return static_cast<int>(index_.nodes.size()) - 1;
  }
  void close(int k) { index_.nodes[static_cast<std::size_t>(k)].skip = static_cast<int>(index_.nodes.size()); }

  Eigen::Vector3d point(int v) const { return tree_.vertices.row(v).transpose(); }

  const FlintstoneTree3& tree_;
  FlintstoneInclusion3& index_;
  std::vector<int> expand_;
};

}  // namespace

FlintstoneInclusion3 inclusion_index(const FlintstoneTree3& tree) {
  FlintstoneInclusion3 index;
  index.vertices = tree.vertices;
  index.faces = tree.faces;
  index.root_ball = tree.root().stone.first;
  index.box = tree.root().box;
  Packer(tree, index).add(0);
  return index;
}

std::size_t FlintstoneInclusion3::storage_bytes() const {
  return nodes.size() * sizeof(Node) + lens_of.size() * sizeof(int) + lenses.size() * sizeof(Lens) + triangles.size() * sizeof(triangles[0]) +
         static_cast<std::size_t>(vertices.size()) * sizeof(double) + static_cast<std::size_t>(faces.size()) * sizeof(int);
}

bool inside(const FlintstoneInclusion3& index, const Eigen::Vector3d& x, InclusionStats* stats) {
  InclusionStats local;
  InclusionStats& count = stats ? *stats : local;
  ++count.flintstone_tests;
  if (outside(index.box, x) || !index.root_ball.contains(x)) return false;
  const auto answer = first_answer(x, index.box, index.root_ball,
                                   [&](const auto& segment) { return index_parity(index, segment, count); });
  return answer ? *answer : inside_brute_force(index.vertices, index.faces, x);
}

bool inside_brute_force(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::Vector3d& x) {
  const Eigen::Vector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  for (int attempt = 0; attempt < max_attempts; ++attempt) {
    const Eigen::Vector3d q = far_point(x, attempt, 0.5 * (lo + hi), 0.5 * (hi - lo).norm());
    bool odd = false, retry = false;
    for (Eigen::Index f = 0; f < F.rows() && !retry; ++f) {
      const Crossing3 crossing = segment_crossing(V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(),
                                                  V.row(F(f, 2)).transpose(), x, q, EdgeSide{x, q});
      if (crossing == Crossing3::on_boundary) return true;
      retry = crossing == Crossing3::degenerate;
      odd ^= crossing == Crossing3::once;
    }
    if (!retry) return odd;
  }
  throw SolverError("point inclusion: no non-degenerate ray after " + std::to_string(max_attempts) + " directions");
}

}  // namespace scanstation
