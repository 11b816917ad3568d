#include "sim/shapes.h"

#include "core/errors.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace scanstation::sim {

TriangleMesh icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Eigen::MatrixX3d V(12, 3);
  V << -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0,  //
      0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t,    //
      t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1;
  V.rowwise().normalize();
  Eigen::MatrixX3i F(20, 3);
  F << 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11,  //
      1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,   //
      3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9,       //
      4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1;
  TriangleMesh mesh;
  mesh.vertices.positions = V;
  mesh.faces = F;
  return mesh;
}

TriangleMesh icosphere(int subdivisions) {
  if (subdivisions < 0 || subdivisions > 9) throw InvalidInput("icosphere: subdivisions must be in [0, 9]");
  TriangleMesh mesh = icosahedron();
  std::vector<Eigen::Vector3d> V;
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i) V.emplace_back(mesh.vertices.positions.row(i));
  std::vector<Eigen::Vector3i> F;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) F.emplace_back(mesh.faces.row(f));
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, inserted] = midpoint.try_emplace(key, static_cast<int>(V.size()));
      if (inserted) V.push_back((V[static_cast<std::size_t>(a)] + V[static_cast<std::size_t>(b)]).normalized());
      return it->second;
    };
    std::vector<Eigen::Vector3i> finer;
    finer.reserve(F.size() * 4);
    for (const Eigen::Vector3i& t : F) {
      const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      finer.emplace_back(t[0], ab, ca);
      finer.emplace_back(t[1], bc, ab);
      finer.emplace_back(t[2], ca, bc);
      finer.emplace_back(ab, bc, ca);
    }
    F = std::move(finer);
  }
  mesh.vertices.positions.resize(static_cast<Eigen::Index>(V.size()), 3);
  for (std::size_t i = 0; i < V.size(); ++i) mesh.vertices.positions.row(static_cast<Eigen::Index>(i)) = V[i];
  mesh.faces.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (std::size_t f = 0; f < F.size(); ++f) mesh.faces.row(static_cast<Eigen::Index>(f)) = F[f];
  return mesh;
}

TriangleMesh ellipsoid(const Eigen::Vector3d& radii, int subdivisions) {
  TriangleMesh mesh = icosphere(subdivisions);
  mesh.vertices.positions = mesh.vertices.positions * radii.asDiagonal();
  return mesh;
}

TriangleMesh torus(double R, double r, int u, int v) {
  if (u < 3 || v < 3) throw InvalidInput("torus: at least 3 segments each way");
  TriangleMesh mesh;
  mesh.vertices.positions.resize(static_cast<Eigen::Index>(u) * v, 3);
  mesh.faces.resize(static_cast<Eigen::Index>(u) * v * 2, 3);
  auto id = [&](int i, int j) { return ((i + u) % u) * v + (j + v) % v; };
  for (int i = 0; i < u; ++i)
    for (int j = 0; j < v; ++j) {
      const double a = 2.0 * std::numbers::pi * i / u, b = 2.0 * std::numbers::pi * j / v;
      mesh.vertices.positions.row(id(i, j)) << (R + r * std::cos(b)) * std::cos(a), (R + r * std::cos(b)) * std::sin(a),
          r * std::sin(b);
      const int f = 2 * id(i, j);
      mesh.faces.row(f) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      mesh.faces.row(f + 1) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  return mesh;
}

}  // namespace scanstation::sim
