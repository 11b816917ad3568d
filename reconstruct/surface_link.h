// The link of a point on the boundary of a solid made of cells: one edge per
// boundary triangle at the point (the triangle's edge opposite the point).
#pragma once

#include <array>
#include <cstddef>
#include <span>

namespace scanstation {

/// Whether `link` (edges given by their two ends, any comparable type: point
/// indices, vertex handles) is a single cycle, i.e. the boundary is a
/// 2-manifold at the point. An empty link (the point is off the boundary) is
/// no pinch either and counts as one. Quadratic in the link's length, which
/// is a few dozen edges at most.
template <typename End>
bool single_cycle(std::span<const std::array<End, 2>> link) {
  if (link.empty()) return true;
  for (const auto& e : link)
    for (const End& end : e) {
      int degree = 0;
      for (const auto& g : link) degree += (g[0] == end) + (g[1] == end);
      if (degree != 2) return false;
    }
  // Every link vertex has degree 2: a union of cycles; walk the first one.
  std::size_t length = 0;
  End previous = link[0][0], at = link[0][1];
  do {
    ++length;
    for (const auto& g : link)
      if ((g[0] == at && g[1] != previous) || (g[1] == at && g[0] != previous)) {
        previous = at;
        at = g[0] == at ? g[1] : g[0];
        break;
      }
  } while (at != link[0][1] && length <= link.size());
  return length == link.size();
}

}  // namespace scanstation
