// Gaps between the parts of an object: Delaunay cells that the outside reaches
// through faces far wider than the sampling around them. Constriction removes
// those first (ConstrictionOptions::carve_first), before the points on either
// side reach the boundary elsewhere and §5.3 then forbids opening the gap:
// constriction would seal it with a web of long thin triangles
// (docs/design.md, "Where recall is lost": a bunny's ear and its head, a
// dinosaur's legs). A scanstation extension of Chapter 5, after the locally
// scaled α of conformal α-shapes (Cazals, Giesen, Pauly, Zomorodian 2005): a
// triangle of a surface sampled densely for its features is about as wide as
// the spacing of the samples at its corners; a face joining two parts is as
// wide as the gap between them. Points on flat faces are the exception: the
// faces joining two flat faces' points along the edge between them are long
// and thin, and the slivers under them are carved first too. That brings
// those points to the boundary early, through shallow cells, which §5.3 then
// keeps from being dug under (a flat-faced ellipsoid of 100k points: 0.34% of
// its volume lost instead of 2.1%).
#pragma once

#include "reconstruct/delaunay_complex.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace scanstation {

struct GapOptions {
  /// The spacing at a point: the length of its k-th shortest distinct
  /// Delaunay edge. The nearest neighbour alone (k = 1) understates it where
  /// points lie in rows (CAD meshes, scan lines) and lets the carving leak
  /// through the object's own long triangles.
  int neighbour = 5;
  /// A face is wide when the smallest ball holding it has a radius of more
  /// than this many times the largest spacing at its three corners.
  double width = 4.0;
  /// A gap reaches at least this many cells deep: the reached cells form
  /// parts (joined by wide faces), and a part whose cells all lie fewer
  /// than this many cells from the hull is not carved.
  int depth = 5;
};

/// dt       a 3D Delaunay complex
/// returns  per cell of dt, −1 when the cell cannot be reached from outside
///          the convex hull through wide faces only, or lies in a part of
///          such cells too shallow for a gap; else the fewest cells between
///          it and the hull on such a path (0: it has a wide hull face).
///          Floating-point radii: the result only orders the removals;
///          removability (§5.3) stays exact.
/// Cost: linear in the cells (one pass over the edges, two walks over the
/// reached cells).
std::vector<int> gap_depths(const DelaunayComplex<3>& dt, const GapOptions& options = {});

/// The spacing of GapOptions from one point's edge lengths, offered one by
/// one (an edge may be offered once per cell around it): s[0, k) keeps the
/// k shortest distinct ones, ascending, infinite until filled.
inline void offer_length(double* s, std::size_t k, double length) {
  if (length >= s[k - 1]) return;  // most lengths, once the shortest are known
  for (std::size_t i = 0; i < k; ++i) {
    if (s[i] == length) return;
    if (length < s[i]) {
      std::copy_backward(s + i, s + k - 1, s + k);
      s[i] = length;
      return;
    }
  }
}

/// The k-th shortest length offered, or the longest one when fewer were
/// offered; 0 when none was.
inline double kth_length(const double* s, std::size_t k) {
  for (std::size_t i = k; i-- > 0;)
    if (std::isfinite(s[i])) return s[i];
  return 0.0;
}

/// Whether the smallest ball holding the triangle abd has a squared radius
/// of more than `width` times `spacing` (both squared; false when spacing is
/// not positive).
bool wider_than(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& d, double spacing,
                double width);

/// The ranks for ConstrictionOptions::carve_first: the cells `first` ranks
/// (≥ 0; e.g. the lines of sight), in its order, then the other cells `then`
/// ranks, in its order. Either may be empty (no cell). Empty when no cell
/// is ranked.
std::vector<int> carve_first_then(std::vector<int> first, const std::vector<int>& then);

}  // namespace scanstation
