#include "reconstruct/flintstone.h"

#include "core/errors.h"
#include "core/predicates.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace scanstation {

namespace {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

/// The family of discs/balls through the corners: centres cc + λ·n, radius²
/// r² + λ², where cc is the chord midpoint (2D) or circumcentre (3D).
template <int D>
struct BallFamily {
  Vec<D> cc;
  Vec<D> n;
  double r2 = 0.0;
  bool valid = false;
};

BallFamily<2> ball_family(const Eigen::Matrix<double, Eigen::Dynamic, 2>& V, const std::array<int, 2>& c) {
  const Vec<2> p = V.row(c[0]).transpose(), s = V.row(c[1]).transpose();
  BallFamily<2> family;
  const Vec<2> d = s - p;
  family.cc = 0.5 * (p + s);
  family.r2 = 0.25 * d.squaredNorm();
  family.n = Vec<2>(-d.y(), d.x()).normalized();  // left of p→s: orientation(p, s, ·) > 0
  family.valid = family.r2 > 0.0;
  return family;
}

BallFamily<3> ball_family(const Eigen::Matrix<double, Eigen::Dynamic, 3>& V, const std::array<int, 3>& c) {
  const Vec<3> p = V.row(c[0]).transpose(), s = V.row(c[1]).transpose(), t = V.row(c[2]).transpose();
  BallFamily<3> family;
  const Vec<3> a = s - p, b = t - p, axb = a.cross(b);
  const double area2 = axb.squaredNorm();
  family.valid = area2 > 1e-24 * a.squaredNorm() * b.squaredNorm();
  if (!family.valid) return family;
  family.cc = p + (a.squaredNorm() * b - b.squaredNorm() * a).cross(axb) / (2.0 * area2);
  family.r2 = (p - family.cc).squaredNorm();
  family.n = axb.normalized();  // orientation(p, s, t, ·) > 0 on this side
  return family;
}

int side(const Eigen::Matrix<double, Eigen::Dynamic, 2>& V, const std::array<int, 2>& c, int v) {
  return orientation(Vec<2>(V.row(c[0])), Vec<2>(V.row(c[1])), Vec<2>(V.row(v)));
}

int side(const Eigen::Matrix<double, Eigen::Dynamic, 3>& V, const std::array<int, 3>& c, int v) {
  return orientation(Vec<3>(V.row(c[0])), Vec<3>(V.row(c[1])), Vec<3>(V.row(c[2])), Vec<3>(V.row(v)));
}

/// Relative slack that keeps float containment decisions on the safe side.
template <int D>
double slack(const SignedBall<D>& ball) {
  return 1e-9 * (ball.radius + ball.center.template lpNorm<Eigen::Infinity>());
}

/// Grows `ball` until every vertex in `vertices` lies inside it, plus slack.
template <int D>
void enclose(SignedBall<D>& ball, const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const std::vector<int>& vertices) {
  double r2 = ball.radius * ball.radius;
  for (const int v : vertices) r2 = std::max(r2, (Vec<D>(V.row(v).transpose()) - ball.center).squaredNorm());
  ball.radius = std::sqrt(r2);
  ball.radius += slack(ball);
}

template <int D>
double distance_to_segment_squared(const Vec<D>& c, const Vec<D>& a, const Vec<D>& b) {
  const Vec<D> ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((c - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - c).squaredNorm();
}

}  // namespace

template <int D>
bool balls_meet(const SignedBall<D>& a, const SignedBall<D>& b) {
  const double reach = a.radius + b.radius;
  return (a.center - b.center).squaredNorm() <= reach * reach * (1.0 + 1e-9);
}

template <int D>
bool segment_misses(const SignedBall<D>& ball, const Vec<D>& a, const Vec<D>& b) {
  return distance_to_segment_squared<D>(ball.center, a, b) > ball.radius * ball.radius * (1.0 + 1e-9);
}

template <int D>
Flintstone<D> ball_flintstone(const Vec<D>& center, double radius) {
  SignedBall<D> ball;
  ball.center = center;
  ball.radius = radius;
  ball.radius += slack(ball);
  ball.signed_radius = ball.radius;
  ball.width = 2.0 * ball.radius;
  Flintstone<D> f;
  f.first = f.second = ball;
  f.degenerate = true;
  return f;
}

template <int D>
Flintstone<D> enclosing_flintstone(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const std::vector<int>& members) {
  Vec<D> centroid = Vec<D>::Zero();
  for (const int v : members) centroid += V.row(v).transpose();
  if (!members.empty()) centroid /= static_cast<double>(members.size());
  double r2 = 0.0;
  for (const int v : members) r2 = std::max(r2, (Vec<D>(V.row(v).transpose()) - centroid).squaredNorm());
  return ball_flintstone<D>(centroid, std::sqrt(r2));
}

// Definition 7.3 (2D) / 7.5 (3D). Ball B(λ) = ball with centre cc + λ·n. A
// vertex v at height h = (v − cc)·n ≠ 0 lies in B(λ) iff λ ≥ key(v) for h > 0
// and λ ≤ key(v) for h < 0, key(v) = (|v − cc|² − r²) / (2h). So B(v_q) has
// λ = max key over the positive side, B(v_r) λ = min key over the negative
// side, and the flintstone is their intersection iff λ_q ≤ λ_r (Definition 7.2
// in terms of signed radii), otherwise their union.
template <int D>
Flintstone<D> flintstone_of(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const std::array<int, D>& corners,
                            const std::vector<int>& members, int& split, const std::vector<char>* eligible) {
  split = -1;
  const BallFamily<D> family = ball_family(V, corners);
  std::vector<int> all(corners.begin(), corners.end()), plus(all), minus(all);
  all.insert(all.end(), members.begin(), members.end());
  if (!family.valid) return enclosing_flintstone<D>(V, all);

  constexpr double none = std::numeric_limits<double>::quiet_NaN();
  double key_plus = none, key_minus = none;  // over all members
  double best_plus = none, best_minus = none;
  int split_plus = -1, split_minus = -1, split_any = -1;
  struct Candidate {
    int vertex, side;
    double key, height;
  };
  std::vector<Candidate> candidates;
  bool off_chord = false;
  for (const int v : members) {
    if (std::find(corners.begin(), corners.end(), v) != corners.end()) continue;
    const bool may_split = eligible == nullptr || (*eligible)[v];
    if (may_split && split_any < 0) split_any = v;
    const Vec<D> x = V.row(v).transpose() - family.cc;
    const int s = side(V, corners, v);
    if (s == 0) {
      // On the chord line/plane: every ball of the family holds it iff it lies
      // within the chord/circumcircle; otherwise no finite flintstone exists.
      // (The split vertex is still chosen below.)
      if (x.squaredNorm() > family.r2 * (1.0 + 1e-9)) off_chord = true;
      plus.push_back(v);
      minus.push_back(v);
      continue;
    }
    // The exact side decides; a height rounded to the wrong sign or to 0 is
    // clamped, so the key stays finite (the ball only grows).
    const double least = 1e-12 * std::sqrt(family.r2);
    const double h = s > 0 ? std::max(x.dot(family.n), least) : std::min(x.dot(family.n), -least);
    const double key = (x.squaredNorm() - family.r2) / (2.0 * h);
    (s > 0 ? plus : minus).push_back(v);
    double& side_key = s > 0 ? key_plus : key_minus;
    if (std::isnan(side_key) || (s > 0 ? key > side_key : key < side_key)) side_key = key;
    if (!may_split) continue;
    candidates.push_back({v, s, key, std::abs(h)});
    double& best = s > 0 ? best_plus : best_minus;
    if (std::isnan(best) || (s > 0 ? key > best : key < best)) {
      best = key;
      (s > 0 ? split_plus : split_minus) = v;
    }
  }

  const double r = std::sqrt(family.r2);
  Flintstone<D> f = off_chord ? enclosing_flintstone<D>(V, all) : Flintstone<D>{};
  if (!off_chord) {
    // A side without vertices is the half-plane/half-space (radius −∞); it is
    // stored as a ball through the chord far enough out (bulge ≤ r/16) that it
    // holds the other ball's side.
    f.first.halfspace = std::isnan(key_plus);
    f.second.halfspace = std::isnan(key_minus);
    if (f.first.halfspace) key_plus = (f.second.halfspace ? 0.0 : std::min(key_minus, 0.0)) - 8.0 * r;
    if (f.second.halfspace) key_minus = std::max(key_plus, 0.0) + 8.0 * r;
    f.is_union = key_plus > key_minus;
    const double radius_plus = std::sqrt(family.r2 + key_plus * key_plus);
    const double radius_minus = std::sqrt(family.r2 + key_minus * key_minus);
    f.first.center = family.cc + key_plus * family.n;
    f.first.radius = radius_plus;
    f.first.signed_radius = key_plus >= 0.0 ? radius_plus : -radius_plus;  // Definition 7.1
    f.first.width = f.first.halfspace ? 0.0 : radius_plus + key_plus;       // Definition 7.4
    f.second.center = family.cc + key_minus * family.n;
    f.second.radius = radius_minus;
    f.second.signed_radius = key_minus <= 0.0 ? radius_minus : -radius_minus;
    f.second.width = f.second.halfspace ? 0.0 : radius_minus - key_minus;
    enclose(f.first, V, f.is_union ? plus : all);
    enclose(f.second, V, f.is_union ? minus : all);
  }

  // Algorithm 7.1/7.2: the side whose ball has the larger signed radius.
  if (split_plus < 0 && split_minus < 0) {
    split = split_any;
  } else if (split_plus < 0 || split_minus < 0) {
    split = split_plus < 0 ? split_minus : split_plus;
  } else {
    const double rq = std::copysign(std::sqrt(family.r2 + best_plus * best_plus), best_plus);
    const double rr = std::copysign(std::sqrt(family.r2 + best_minus * best_minus), -best_minus);
    split = rq >= rr ? split_plus : split_minus;
  }
  // Vertices barely off the chord line/plane get unstable keys (a tiny
  // height divides a small excess), and near-ties (a spherical cap: every
  // vertex on about the same ball) are decided by rounding. Either way
  // Algorithm 7.1/7.2's vertex can sit next to P's boundary and split off a
  // sliver. So a side whose vertices all stay below half the other side's
  // height gives way to the other side, on the side only vertices at
  // least a quarter of its greatest height compete, and keys within 2% of the
  // ball radius count as equal, the higher vertex winning. Only in 3D: in 2D
  // Algorithm 7.1's own rule keeps every flintstone an intersection (§7.2.2).
  if (D == 3 && split >= 0) {
    std::array<double, 2> tops{0.0, 0.0};  // greatest height on the −/+ side
    for (const Candidate& c : candidates) tops[c.side > 0] = std::max(tops[c.side > 0], c.height);
    int s = split == split_plus ? 1 : -1;
    if (tops[s > 0] < 0.5 * tops[s < 0]) s = -s;  // the chosen side is a sliver by the chord/plane
    const double top = tops[s > 0];
    double best = std::numeric_limits<double>::quiet_NaN();
    for (const Candidate& c : candidates)
      if (c.side == s && c.height >= 0.25 * top && (std::isnan(best) || (s > 0 ? c.key > best : c.key < best)))
        best = c.key;
    const double tolerance = 0.02 * std::sqrt(family.r2 + best * best);
    double height = -1.0;
    for (const Candidate& c : candidates)
      if (c.side == s && c.height >= 0.25 * top && std::abs(c.key - best) <= tolerance && c.height > height) {
        height = c.height;
        split = c.vertex;
      }
  }
  return f;
}

template <int D>
bool flintstones_meet(const Flintstone<D>& f, const Flintstone<D>& g) {
  const bool b1c1 = balls_meet(f.first, g.first), b2c1 = balls_meet(f.second, g.first);
  const bool b1c2 = balls_meet(f.first, g.second), b2c2 = balls_meet(f.second, g.second);
  if (!f.is_union && !g.is_union) return b1c1 && b2c1 && b1c2 && b2c2;  // §7.4 case 1
  if (f.is_union && g.is_union) return b1c1 || b2c1 || b1c2 || b2c2;    // case 2
  if (!f.is_union) return (b1c1 && b2c1) || (b1c2 && b2c2);             // case 3
  return (b1c1 && b1c2) || (b2c1 && b2c2);
}

template <int D>
bool segment_misses(const Flintstone<D>& f, const Vec<D>& a, const Vec<D>& b) {
  return f.is_union ? segment_misses(f.first, a, b) && segment_misses(f.second, a, b)
                    : segment_misses(f.first, a, b) || segment_misses(f.second, a, b);
}

template <int D>
void require_ball_range(const Eigen::Matrix<double, Eigen::Dynamic, D>& V, const char* what) {
  if (V.rows() == 0) return;
  // The largest coordinate and the box's largest side: the ball computations
  // (the smallest enclosing balls, the flintstones' keys) reach fourth
  // powers of lengths. Measured: a triangle builds from 1e-60 to 1e77 across
  // and is refused beyond; the limits keep a margin.
  const double largest = V.cwiseAbs().maxCoeff();
  const double side = (V.colwise().maxCoeff() - V.colwise().minCoeff()).maxCoeff();
  constexpr double kHigh = 1e70, kLow = 1e-50;
  if (largest > kHigh || (side > 0.0 && side < kLow)) {
    char magnitude[32];
    std::snprintf(magnitude, sizeof magnitude, "%.3g", largest > kHigh ? largest : side);
    throw InvalidInput(std::string("flintstone tree: the ") + what + (largest > kHigh ? "'s coordinates reach " : " spans only ") +
                       magnitude + ", beyond what its ball computations hold (sizes 1e-50 to 1e70): scale it first");
  }
}

#define SCANSTATION_FLINTSTONE(D)                                                                                 \
  template Flintstone<D> flintstone_of<D>(const Eigen::Matrix<double, Eigen::Dynamic, D>&,                        \
                                          const std::array<int, D>&, const std::vector<int>&, int&,               \
                                          const std::vector<char>*);                                              \
  template bool flintstones_meet<D>(const Flintstone<D>&, const Flintstone<D>&);                                  \
  template bool segment_misses<D>(const Flintstone<D>&, const Vec<D>&, const Vec<D>&);                            \
  template bool segment_misses<D>(const SignedBall<D>&, const Vec<D>&, const Vec<D>&);                            \
  template bool balls_meet<D>(const SignedBall<D>&, const SignedBall<D>&);                                        \
  template Flintstone<D> ball_flintstone<D>(const Vec<D>&, double);                                               \
  template Flintstone<D> enclosing_flintstone<D>(const Eigen::Matrix<double, Eigen::Dynamic, D>&,                 \
                                                 const std::vector<int>&);                                        \
  template void require_ball_range<D>(const Eigen::Matrix<double, Eigen::Dynamic, D>&, const char*);
SCANSTATION_FLINTSTONE(2)
SCANSTATION_FLINTSTONE(3)
#undef SCANSTATION_FLINTSTONE

}  // namespace scanstation
