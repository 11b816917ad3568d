#include "smoothing/tessellation.h"

#include "core/errors.h"
#include "smoothing/patch_adjacency.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <string_view>
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

void check_density(int density) {
  if (density < 1) throw InvalidInput("--density must be at least 1, got " + std::to_string(density));
}

// Vertex numbers of the streamed tessellation.
struct StreamNumbering {
  int n;
  std::vector<int> corner;                  // patch*3 + k -> corner vertex number
  std::vector<std::pair<int, int>> corner_owner;  // corner number -> (patch, k)
  std::vector<int> edge;                    // patch*3 + k -> shared edge number
  std::vector<bool> edge_forward;           // patch*3 + k runs the edge's own way
  std::vector<std::pair<int, int>> edge_owner;  // edge number -> (patch, k) running its own way
  std::size_t corners() const { return corner_owner.size(); }
  std::size_t edge_base() const { return corners(); }
  std::size_t interior_base() const { return corners() + edge_owner.size() * std::size_t(n - 1); }

  // Number of grid point (a, b) of patch p.
  std::size_t at(int p, int a, int b) const {
    const auto along = [&](int k, int step) {
      const int e = edge[3 * p + k];
      const int offset = edge_forward[3 * p + k] ? step - 1 : n - step - 1;
      return edge_base() + std::size_t(e) * (n - 1) + offset;
    };
    if (b == 0 && a == 0) return corner[3 * p];
    if (b == 0 && a == n) return corner[3 * p + 1];
    if (a == 0 && b == n) return corner[3 * p + 2];
    if (b == 0) return along(0, a);
    if (a + b == n) return along(1, b);
    if (a == 0) return along(2, n - b);
    // Inner points row by row: a from 1, b from 1 to n−a−1.
    const std::size_t per_patch = std::size_t(n - 1) * (n - 2) / 2;
    std::size_t local = 0;
    for (int row = 1; row < a; ++row) local += n - row - 1;
    return interior_base() + std::size_t(p) * per_patch + local + (b - 1);
  }
};

StreamNumbering stream_numbering(const BezierSurface& surface, int n) {
  StreamNumbering numbering;
  numbering.n = n;
  const std::size_t patches = surface.patches.size();
  numbering.corner.resize(3 * patches);
  numbering.edge.assign(3 * patches, -1);
  numbering.edge_forward.assign(3 * patches, true);
  std::unordered_map<Eigen::Vector3d, int, PositionHash, PositionEqual> corner_of;
  for (std::size_t p = 0; p < patches; ++p)
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] =
          corner_of.emplace(patch_corner(surface.patches[p], k), static_cast<int>(numbering.corner_owner.size()));
      if (inserted) numbering.corner_owner.emplace_back(int(p), k);
      numbering.corner[3 * p + k] = it->second;
    }
  for (const PatchEdgePair& pair : patch_adjacency(surface).pairs) {
    const int e = static_cast<int>(numbering.edge_owner.size());
    numbering.edge_owner.emplace_back(pair.patch_a, pair.edge_a);
    numbering.edge[3 * pair.patch_a + pair.edge_a] = e;
    numbering.edge[3 * pair.patch_b + pair.edge_b] = e;
    numbering.edge_forward[3 * pair.patch_b + pair.edge_b] = false;
  }
  for (std::size_t i = 0; i < 3 * patches; ++i)  // edges of an open surface: their own
    if (numbering.edge[i] < 0) {
      numbering.edge[i] = static_cast<int>(numbering.edge_owner.size());
      numbering.edge_owner.emplace_back(int(i / 3), int(i % 3));
    }
  return numbering;
}

void append_raw(std::string& out, const void* data, std::size_t bytes) {
  out.append(static_cast<const char*>(data), bytes);
}

void append_vertex(std::string& out, const Eigen::Vector3d& x, const Eigen::Vector3d& normal) {
  append_raw(out, x.data(), 3 * sizeof(double));
  append_raw(out, normal.data(), 3 * sizeof(double));
}

}  // namespace

void write_tessellation_ply(const BezierSurface& surface, int density, const std::filesystem::path& path,
                            io::Overwrite overwrite) {
  static_assert(std::endian::native == std::endian::little, "the PLY is written in the machine's byte order");
  check_density(density);
  const int n = density;
  const StreamNumbering numbering = stream_numbering(surface, n);
  const std::size_t vertices =
      numbering.interior_base() + surface.patches.size() * std::size_t(n - 1) * (n - 2) / 2;
  const std::size_t faces = surface.patches.size() * std::size_t(n) * n;
  const auto parameter = [n](int a, int b) { return Barycentric(double(n - a - b) / n, double(a) / n, double(b) / n); };
  const auto grid_of_edge = [n](int k, int step) -> std::pair<int, int> {
    return k == 0 ? std::pair{step, 0} : k == 1 ? std::pair{n - step, step} : std::pair{0, n - step};
  };
  io::write_file_atomically_streamed(
      path,
      [&](const io::ByteSink& sink) {
        std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by scanstation smooth\n";
        // Appended piecewise: GCC 12 misreports a chained '+' here (-Wrestrict).
        out.append("element vertex ").append(std::to_string(vertices));
        out.append("\nproperty double x\nproperty double y\nproperty double z\nproperty double nx\n");
        out.append("property double ny\nproperty double nz\nelement face ").append(std::to_string(faces));
        out.append("\nproperty list uchar int vertex_indices\nend_header\n");
        const auto flush_if_full = [&] {
          if (out.size() > (1u << 20)) {
            sink(out);
            out.clear();
          }
        };
        for (const auto& [p, k] : numbering.corner_owner) {
          const auto [a, b] = grid_of_edge(k, 0);
          append_vertex(out, patch_corner(surface.patches[p], k),
                        unit_normal(surface.patches[p], parameter(a, b)));
          flush_if_full();
        }
        for (const auto& [p, k] : numbering.edge_owner)
          for (int step = 1; step < n; ++step) {
            const auto [a, b] = grid_of_edge(k, step);
            append_vertex(out, edge_point(surface.patches[p], k, step, n),
                          unit_normal(surface.patches[p], parameter(a, b)));
            flush_if_full();
          }
        for (const CubicTriangle& patch : surface.patches)
          for (int a = 1; a < n; ++a)
            for (int b = 1; a + b < n; ++b) {
              append_vertex(out, evaluate(patch, parameter(a, b)), unit_normal(patch, parameter(a, b)));
              flush_if_full();
            }
        const auto append_face = [&](std::size_t i, std::size_t j, std::size_t k) {
          const unsigned char three = 3;
          const std::int32_t index[3] = {std::int32_t(i), std::int32_t(j), std::int32_t(k)};
          append_raw(out, &three, 1);
          append_raw(out, index, sizeof index);
        };
        for (int p = 0; p < static_cast<int>(surface.patches.size()); ++p) {
          for (int a = 0; a < n; ++a)
            for (int b = 0; a + b < n; ++b) {
              append_face(numbering.at(p, a, b), numbering.at(p, a + 1, b), numbering.at(p, a, b + 1));
              if (a + b < n - 1)
                append_face(numbering.at(p, a + 1, b), numbering.at(p, a + 1, b + 1), numbering.at(p, a, b + 1));
            }
          flush_if_full();
        }
        sink(out);
      },
      overwrite);
}

TriangleMesh tessellate(const BezierSurface& surface, int density) {
  check_density(density);
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
          normals.push_back(unit_normal(patch, uvw));
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
