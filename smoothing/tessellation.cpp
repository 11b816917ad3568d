#include "smoothing/tessellation.h"

#include "core/errors.h"

#include <cstring>
#include <unordered_map>
#include <vector>

namespace scanstation {

namespace {

struct PositionHash {
  std::size_t operator()(const Eigen::Vector3d& p) const {
    std::size_t hash = 1469598103934665603ull;
    for (int i = 0; i < 3; ++i) {
      std::uint64_t bits;
      std::memcpy(&bits, &p[i], sizeof bits);
      hash = (hash ^ bits) * 1099511628211ull;
    }
    return hash;
  }
};

struct PositionEqual {
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
  }
};

bool lexicographically_less(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// The control points of edge k, from corner k to corner k+1.
std::array<Eigen::Vector3d, 4> edge_controls(const CubicTriangle& b, int k) {
  switch (k) {
    case 0: return {b[control_index(3, 0, 0)], b[control_index(2, 1, 0)], b[control_index(1, 2, 0)], b[control_index(0, 3, 0)]};
    case 1: return {b[control_index(0, 3, 0)], b[control_index(0, 2, 1)], b[control_index(0, 1, 2)], b[control_index(0, 0, 3)]};
    default: return {b[control_index(0, 0, 3)], b[control_index(1, 0, 2)], b[control_index(2, 0, 1)], b[control_index(3, 0, 0)]};
  }
}

// Point `step` of `n` along edge k, computed in the edge's canonical direction.
Eigen::Vector3d edge_point(const CubicTriangle& patch, int k, int step, int n) {
  std::array<Eigen::Vector3d, 4> c = edge_controls(patch, k);
  if (lexicographically_less(c[3], c[0])) {
    std::swap(c[0], c[3]);
    std::swap(c[1], c[2]);
    step = n - step;
  }
  const double t = double(step) / n;
  for (int level = 3; level > 0; --level)
    for (int j = 0; j < level; ++j) c[j] = (1.0 - t) * c[j] + t * c[j + 1];
  return c[0];
}

// Grid point (a, b): barycentric ((n−a−b)/n, a/n, b/n).
Eigen::Vector3d grid_point(const CubicTriangle& patch, int a, int b, int n) {
  if (b == 0) return edge_point(patch, 0, a, n);
  if (a + b == n) return edge_point(patch, 1, b, n);
  if (a == 0) return edge_point(patch, 2, n - b, n);
  return evaluate(patch, Barycentric(double(n - a - b) / n, double(a) / n, double(b) / n));
}

}  // namespace

TriangleMesh tessellate(const BezierSurface& surface, int density) {
  if (density < 1) throw InvalidInput("--density must be at least 1, got " + std::to_string(density));
  const int n = density;
  const int per_patch = (n + 1) * (n + 2) / 2;
  std::unordered_map<Eigen::Vector3d, int, PositionHash, PositionEqual> index_of;
  index_of.reserve(surface.patches.size() * per_patch / 2);
  std::vector<Eigen::Vector3d> positions, normals;
  std::vector<Eigen::Vector3i> faces;
  faces.reserve(surface.patches.size() * n * n);
  std::vector<int> local(per_patch);
  for (const CubicTriangle& patch : surface.patches) {
    int slot = 0;
    for (int a = 0; a <= n; ++a)
      for (int b = 0; a + b <= n; ++b) {
        const Eigen::Vector3d x = grid_point(patch, a, b, n);
        const auto [it, inserted] = index_of.emplace(x, static_cast<int>(positions.size()));
        if (inserted) {
          positions.push_back(x);
          const Barycentric uvw(double(n - a - b) / n, double(a) / n, double(b) / n);
          normals.push_back(normal_direction(patch, uvw).normalized());
        }
        local[slot++] = it->second;
      }
    const auto at = [&](int a, int b) { return local[a * (2 * n + 3 - a) / 2 + b]; };
    for (int a = 0; a < n; ++a)
      for (int b = 0; a + b < n; ++b) {
        faces.emplace_back(at(a, b), at(a + 1, b), at(a, b + 1));
        if (a + b < n - 1) faces.emplace_back(at(a + 1, b), at(a + 1, b + 1), at(a, b + 1));
      }
  }
  TriangleMesh mesh;
  mesh.vertices.positions.resize(positions.size(), 3);
  mesh.vertices.normals.resize(positions.size(), 3);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    mesh.vertices.positions.row(i) = positions[i].transpose();
    mesh.vertices.normals.row(i) = normals[i].transpose();
  }
  mesh.faces.resize(faces.size(), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) mesh.faces.row(i) = faces[i].transpose();
  return mesh;
}

}  // namespace scanstation
