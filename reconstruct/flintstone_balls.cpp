#include "reconstruct/flintstone_balls.h"

#include <cmath>
#include <numbers>

namespace scanstation {

namespace {
constexpr int longitudes = 12;
constexpr int latitudes = 8;
}  // namespace

TriangleMesh flintstone_balls_mesh(const FlintstoneTree3& tree, const MeshApproximation& approximation) {
  std::vector<std::pair<const SignedBall<3>*, bool>> balls;
  for (const int id : approximation.nodes) {
    const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(id)];
    if (node.leaf()) continue;
    if (!node.stone.first.halfspace) balls.push_back({&node.stone.first, true});
    if (!node.stone.second.halfspace && !node.stone.degenerate) balls.push_back({&node.stone.second, false});
  }
  constexpr int ring = longitudes * (latitudes - 1) + 2;  // poles plus rings
  TriangleMesh mesh;
  const auto count = static_cast<Eigen::Index>(balls.size());
  mesh.vertices.positions.resize(count * ring, 3);
  mesh.vertices.colors.resize(count * ring, 3);
  mesh.faces.resize(count * 2 * longitudes * (latitudes - 1), 3);
  Eigen::Index face = 0;
  const Eigen::Matrix<std::uint8_t, 1, 3> red(200, 60, 50), blue(50, 90, 200);
  for (Eigen::Index b = 0; b < count; ++b) {
    const SignedBall<3>& ball = *balls[static_cast<std::size_t>(b)].first;
    const Eigen::Index base = b * ring;
    const auto at = [&](int lat, int lon) -> int {
      if (lat == 0) return static_cast<int>(base);
      if (lat == latitudes) return static_cast<int>(base + ring - 1);
      return static_cast<int>(base + 1 + (lat - 1) * longitudes + (lon % longitudes));
    };
    for (int lat = 0; lat <= latitudes; ++lat)
      for (int lon = 0; lon < (lat == 0 || lat == latitudes ? 1 : longitudes); ++lon) {
        const double theta = std::numbers::pi * lat / latitudes, phi = 2.0 * std::numbers::pi * lon / longitudes;
        const Eigen::Vector3d direction(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        mesh.vertices.positions.row(at(lat, lon)) = (ball.center + ball.radius * direction).transpose();
        mesh.vertices.colors.row(at(lat, lon)) = balls[static_cast<std::size_t>(b)].second ? red : blue;
      }
    for (int lat = 0; lat < latitudes; ++lat)
      for (int lon = 0; lon < longitudes; ++lon) {
        if (lat > 0) mesh.faces.row(face++) << at(lat, lon), at(lat + 1, lon), at(lat, lon + 1);
        if (lat + 1 < latitudes) mesh.faces.row(face++) << at(lat, lon + 1), at(lat + 1, lon), at(lat + 1, lon + 1);
      }
  }
  mesh.faces.conservativeResize(face, 3);
  return mesh;
}

}  // namespace scanstation
