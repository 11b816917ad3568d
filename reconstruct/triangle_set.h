// Triangles as unordered vertex triples, for membership tests: the faces
// that must stay on the boundary (§5.7), asked about by the passes after
// constriction; the faces a patch had before unfolding replaced it.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <vector>

namespace scanstation {

class TriangleSet {
 public:
  TriangleSet() = default;
  /// triangles  #K by 3 vertex indices, in any order within a row
  explicit TriangleSet(const Eigen::MatrixXi& triangles) {
    for (Eigen::Index k = 0; k < triangles.rows(); ++k) sorted_.push_back(key(triangles(k, 0), triangles(k, 1), triangles(k, 2)));
    std::sort(sorted_.begin(), sorted_.end());
  }
  /// triangles  vertex triples, in any order within each
  explicit TriangleSet(const std::vector<std::array<int, 3>>& triangles) {
    for (const auto& t : triangles) sorted_.push_back(key(t[0], t[1], t[2]));
    std::sort(sorted_.begin(), sorted_.end());
  }
  bool empty() const { return sorted_.empty(); }
  bool contains(int a, int b, int c) const {
    return !sorted_.empty() && std::binary_search(sorted_.begin(), sorted_.end(), key(a, b, c));
  }
  bool contains(const std::array<int, 3>& t) const { return contains(t[0], t[1], t[2]); }

 private:
  static std::array<int, 3> key(int a, int b, int c) {
    std::array<int, 3> t{a, b, c};
    std::sort(t.begin(), t.end());
    return t;
  }
  std::vector<std::array<int, 3>> sorted_;
};

}  // namespace scanstation
