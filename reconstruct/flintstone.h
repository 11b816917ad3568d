// The flintstone: a bounding area (2D) or volume (3D) made of two discs or
// balls with signed radii through the end vertices of a polyline (2D) or the
// corner vertices of an open polyhedron (3D). Thesis §7.2.1 and §7.3.1.
//
// Discs through a segment p s (2D) and balls through the circumcircle of a
// triangle p s t (3D) form the same one-parameter family: centres on the line
// cc + λ·n through the chord/circumcentre cc, normal to the chord/plane. This
// file works on that shared form, templated on the dimension D = 2 or 3.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <vector>

namespace scanstation {

/// A disc/ball with centre and radius. `signed_radius` follows Definition 7.1:
/// negative when the centre lies on the other side of the chord/plane than the
/// vertex that defines it. `radius` is the (slightly enlarged, see
/// flintstone_of) unsigned radius used for containment decisions.
template <int D>
struct SignedBall {
  Eigen::Matrix<double, D, 1> center = Eigen::Matrix<double, D, 1>::Zero();
  double radius = 0.0;
  double signed_radius = 0.0;
  /// The half-plane/half-space of Definitions 7.3/7.5 (radius −∞), stored as a
  /// finite ball through the same chord that contains the other ball's side.
  bool halfspace = false;
  /// Largest distance of the ball's boundary from the chord/plane on the side
  /// of its defining vertex: the width w of Definitions 7.4/7.6 (0 for a half-space).
  double width = 0.0;

  bool contains(const Eigen::Matrix<double, D, 1>& x) const { return (x - center).squaredNorm() <= radius * radius; }
};

/// Definition 7.3 / 7.5 with the ±-operator of Definition 7.2: the two balls
/// and whether the flintstone is their intersection or their union.
template <int D>
struct Flintstone {
  SignedBall<D> first;   ///< B(·; v_q): the ball on the side of the normal
  SignedBall<D> second;  ///< B(·; v_r): the ball on the other side
  bool is_union = false;
  /// Definition 7.3/7.5 has no finite form (a vertex on the chord line or plane
  /// outside the chord, or collinear corners): both balls are then one plain
  /// bounding ball of the vertices.
  bool degenerate = false;

  bool contains(const Eigen::Matrix<double, D, 1>& x) const {
    return is_union ? first.contains(x) || second.contains(x) : first.contains(x) && second.contains(x);
  }
  /// Covering error of this flintstone, max{w1, w2} (error e5, Definitions 7.4/7.6).
  double width() const { return std::max(first.width, second.width); }
};

/// The flintstone of the vertices `members` (row indices into V, the corners
/// included or not) through the corners.
///   V        #V by D vertex positions
///   corners  D vertex indices: v_p, v_s (2D) or v_p, v_s, v_t (3D), in boundary order
///   members  the vertices of the polyline / open polyhedron
/// Returns the flintstone and, in `split`, the vertex Algorithm 7.1/7.2 includes
/// next: v_q or v_r (the one whose ball has the larger signed radius, or the
/// only side that holds vertices), chosen among the members that are not
/// corners and, when `eligible` is given, have eligible[v] set; -1 when there
/// is none. Sides are decided with exact orientation predicates;
/// the balls are then enlarged by a relative 1e-9 so that every member lies
/// inside them in floating point too.
template <int D>
Flintstone<D> flintstone_of(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const std::array<int, D>& corners,
                            const std::vector<int>& members, int& split,
                            const std::vector<char>* eligible = nullptr);

/// True when the flintstones may share a point: the ball-distance tests of
/// §7.4 for intersection/intersection, union/union and intersection/union
/// pairs. Conservative (never false when they do meet).
template <int D>
bool flintstones_meet(const Flintstone<D>& f, const Flintstone<D>& g);

/// True when the segment a b certainly misses the flintstone (conservative:
/// may answer false for a segment that misses it).
template <int D>
bool segment_misses(const Flintstone<D>& f, const Eigen::Matrix<double, D, 1>& a, const Eigen::Matrix<double, D, 1>& b);

/// The same tests for single balls.
template <int D>
bool balls_meet(const SignedBall<D>& a, const SignedBall<D>& b);
template <int D>
bool segment_misses(const SignedBall<D>& ball, const Eigen::Matrix<double, D, 1>& a, const Eigen::Matrix<double, D, 1>& b);

/// A flintstone that is a single ball (centre, radius), for the root of a tree
/// and for original edges/faces in pair tests.
template <int D>
Flintstone<D> ball_flintstone(const Eigen::Matrix<double, D, 1>& center, double radius);

/// The smallest ball around the centroid of `members` that holds them all.
template <int D>
Flintstone<D> enclosing_flintstone(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const std::vector<int>& members);

/// Throws InvalidInput when V's coordinates lie beyond what the flintstones'
/// ball computations hold, coordinates above 1e70 or sizes below 1e-50:
/// they reach fourth powers of lengths (a polygon at 1e300 was said to have
/// all its vertices coincide). `what` names the boundary ("polygon", "mesh").
template <int D>
void require_ball_range(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const char* what);

}  // namespace scanstation
