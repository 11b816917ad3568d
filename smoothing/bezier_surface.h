// A piecewise cubic Bézier-triangle surface over a triangle mesh, as the
// splitting schemes of §9.6–§9.8 produce it.
#pragma once

#include "smoothing/bezier_triangle.h"

#include <array>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace scanstation {

/// std::allocator whose resize() default-initialises instead of
/// value-initialising: a std::array of Eigen vectors is then left unwritten
/// (not zeroed), so a scheme that fills its patches in place writes each
/// byte once.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// patches  the micro triangles; corners counter-clockwise from outside
/// macro    for each patch, the index of the input (macro) triangle it splits
/// dependent_edges  macro edges, as the two macro triangles they join (the
///          smaller index first), where the scheme's equations for the
///          cross-edge control points were dependent (e.g. Equation (9.4) on
///          an edge whose two ends look alike, as on a regular icosahedron)
///          or had no solution (an end whose tangent plane condition (9.3a)
///          cannot hold, see end_fits): the closest solution was taken and
///          the edge need not be G¹ (for a two-split pair whose star has no
///          solution, the pair's own two triangles)
/// Adjacent patches share their common edge's four control points bit for bit.
struct BezierSurface {
  std::vector<CubicTriangle, UninitialisedAllocator<CubicTriangle>> patches;
  std::vector<int, UninitialisedAllocator<int>> macro;
  std::vector<std::array<int, 2>> dependent_edges;
};

}  // namespace scanstation
