#include "smoothing/tessellation.h"

#include "core/errors.h"
#include "smoothing/patch_adjacency.h"

#include <algorithm>
#include <array>
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

void check_density(int density) {
  if (density < 1) throw InvalidInput("--density must be at least 1, got " + std::to_string(density));
}

Barycentric grid_parameter(int a, int b, int n) { return {double(n - a - b) / n, double(a) / n, double(b) / n}; }

// Grid point (a, b) of density n at step `step` of `n` along edge k.
std::array<int, 2> grid_of_edge(int k, int step, int n) {
  return k == 0 ? std::array{step, 0} : k == 1 ? std::array{n - step, step} : std::array{0, n - step};
}

// One patch's tessellation in local numbers: corner k is k; the inner
// points of edge k follow, edge by edge, in the patch's own direction;
// then the grid's inner points row by row (a from 1, b from 1 to m−a−1).
class PatchLayout {
 public:
  PatchLayout(int inner, const std::array<int, 3>& edge) : e_(edge) {
    regular_ = edge[0] == inner && edge[1] == inner && edge[2] == inner;
    m_ = regular_ ? inner : std::max(inner, 3);
    edge_start_ = {3, 3 + e_[0] - 1, 3 + e_[0] - 1 + e_[1] - 1};
    inner_start_ = edge_start_[2] + e_[2] - 1;
  }
  int m() const { return m_; }
  int edge_segments(int k) const { return e_[static_cast<std::size_t>(k)]; }
  int points() const { return inner_start_ + inner_points(); }
  int first_inner() const { return inner_start_; }
  int inner_points() const { return (m_ - 1) * (m_ - 2) / 2; }
  int triangles() const { return regular_ ? m_ * m_ : (m_ - 3) * (m_ - 3) + e_[0] + e_[1] + e_[2] + 3 * (m_ - 3); }

  // Step s of edge k (s = 0 and s = e: its corners).
  int along(int k, int s) const {
    if (s == 0) return k;
    if (s == e_[static_cast<std::size_t>(k)]) return (k + 1) % 3;
    return edge_start_[static_cast<std::size_t>(k)] + s - 1;
  }
  // Inner grid point (a, b), a, b ≥ 1, a + b ≤ m − 1.
  int inner(int a, int b) const {
    // Rows 1 … a−1 hold m−2, m−3, … points.
    return inner_start_ + (a - 1) * (m_ - 1) - (a - 1) * a / 2 + (b - 1);
  }
  // Grid point (a, b), on the border too (the regular grid only).
  int grid(int a, int b) const {
    if (b == 0) return along(0, a);
    if (a + b == m_) return along(1, b);
    if (a == 0) return along(2, m_ - b);
    return inner(a, b);
  }

  template <typename Emit>
  void for_each_triangle(Emit&& emit) const {
    if (regular_) {
      for (int a = 0; a < m_; ++a)
        for (int b = 0; a + b < m_; ++b) {
          emit(grid(a, b), grid(a + 1, b), grid(a, b + 1));
          if (a + b < m_ - 1) emit(grid(a + 1, b), grid(a + 1, b + 1), grid(a, b + 1));
        }
      return;
    }
    for (int a = 1; a < m_; ++a)  // the grid inside the border ring
      for (int b = 1; a + b <= m_ - 2; ++b) {
        emit(inner(a, b), inner(a + 1, b), inner(a, b + 1));
        if (a + b <= m_ - 3) emit(inner(a + 1, b), inner(a + 1, b + 1), inner(a, b + 1));
      }
    // Each edge's band, between its points and the border row of the inner
    // grid (from inner corner k to inner corner k+1), both counter-clockwise
    // around the patch; zipped by their positions along the edge: i/e for the
    // edge's points, (j + 1.5)/m for the row's (the row sits half a step in).
    const int q = m_ - 3;
    const auto row = [&](int k, int j) {
      return k == 0 ? inner(1 + j, 1) : k == 1 ? inner(m_ - 2 - j, 1 + j) : inner(1, m_ - 2 - j);
    };
    for (int k = 0; k < 3; ++k) {
      const int e = e_[static_cast<std::size_t>(k)];
      int i = 0, j = 0;
      while (i < e || j < q) {
        // Compare the next steps' midpoints: (2i+1)/(2e) against (2j+4)/(2m).
        const bool outer = j == q || (i < e && (2 * i + 1) * m_ <= (2 * j + 4) * e);
        if (outer) {
          emit(along(k, i), along(k, i + 1), row(k, j));
          ++i;
        } else {
          emit(along(k, i), row(k, j + 1), row(k, j));
          ++j;
        }
      }
    }
  }

  bool on_edge(int local) const { return local >= 3 && local < inner_start_; }
  // Edge k and step s (1 to e_k − 1) of a point on_edge.
  std::array<int, 2> edge_step(int local) const {
    const int k = local < edge_start_[1] ? 0 : local < edge_start_[2] ? 1 : 2;
    return {k, local - edge_start_[static_cast<std::size_t>(k)] + 1};
  }

  // The patch parameter of a local point.
  Barycentric parameter(int local) const {
    if (local < 3) return Barycentric::Unit(local);
    if (on_edge(local)) {
      const auto [k, step] = edge_step(local);
      const int n = e_[static_cast<std::size_t>(k)];
      const auto [a, b] = grid_of_edge(k, step, n);
      return grid_parameter(a, b, n);
    }
    int index = local - inner_start_, a = 1;
    for (; index >= m_ - a - 1; ++a) index -= m_ - a - 1;
    return grid_parameter(a, index + 1, m_);
  }

 private:
  std::array<int, 3> e_;
  std::array<int, 3> edge_start_;
  int inner_start_ = 0, m_ = 1;
  bool regular_ = true;
};

PatchLayout layout_of(const TessellationPlan& plan, std::size_t p) {
  return PatchLayout(plan.inner[p], {plan.edge[3 * p], plan.edge[3 * p + 1], plan.edge[3 * p + 2]});
}

void check_plan(const BezierSurface& surface, const TessellationPlan& plan) {
  if (plan.inner.size() != surface.patches.size() || plan.edge.size() != 3 * surface.patches.size())
    throw InvalidInput("a tessellation plan needs one density per patch and one per patch edge");
  for (const PatchEdgePair& pair : plan.shared) {
    if (std::max(pair.patch_a, pair.patch_b) >= static_cast<int>(surface.patches.size()) || std::min(pair.patch_a, pair.patch_b) < 0)
      throw InvalidInput("a tessellation plan's shared patch edge names a patch the surface does not have");
    if (std::min(pair.edge_a, pair.edge_b) < 0 || std::max(pair.edge_a, pair.edge_b) > 2)
      throw InvalidInput("a tessellation plan's shared patch edge names an edge other than 0, 1 or 2 of its patch");
  }
  for (const int n : plan.inner) check_density(n);
  for (std::size_t i = 0; i < plan.edge.size(); ++i)
    if (plan.edge[i] < plan.inner[i / 3])
      throw InvalidInput("a tessellation plan's patch edge has fewer segments than its patch");
}

// The position of a local point: corners as they are, edge points from the
// edge's control points in its canonical direction (both patches alike).
Eigen::Vector3d local_position(const CubicTriangle& patch, const PatchLayout& layout, int local) {
  if (local < 3) return patch_corner(patch, local);
  if (layout.on_edge(local)) {
    const auto [k, step] = layout.edge_step(local);
    return edge_point(patch, k, step, layout.edge_segments(k));
  }
  return evaluate(patch, layout.parameter(local));
}

// Vertex numbers of the streamed tessellation.
struct StreamNumbering {
  std::vector<int> corner;                        // patch*3 + k -> corner vertex number
  std::vector<std::pair<int, int>> corner_owner;  // corner number -> (patch, k)
  std::vector<int> edge;                          // patch*3 + k -> shared edge number
  std::vector<bool> edge_forward;                 // patch*3 + k runs the edge's own way
  std::vector<std::pair<int, int>> edge_owner;    // edge number -> (patch, k) running its own way
  std::vector<std::size_t> edge_offset;           // edge number -> its first inner point's number (and one past the last)
  std::vector<std::size_t> inner_offset;          // patch -> its first inner point's number (and one past the last)

  std::size_t vertices() const { return inner_offset.back(); }

  // Number of local point `local` of patch p.
  std::size_t global(int p, const PatchLayout& layout, int local) const {
    if (local < 3) return std::size_t(corner[3 * std::size_t(p) + std::size_t(local)]);
    if (!layout.on_edge(local)) return inner_offset[std::size_t(p)] + std::size_t(local - layout.first_inner());
    const auto [k, step] = layout.edge_step(local);
    const std::size_t slot = 3 * std::size_t(p) + std::size_t(k);
    const int e = edge[slot];
    const int offset = edge_forward[slot] ? step - 1 : layout.edge_segments(k) - step - 1;
    return edge_offset[std::size_t(e)] + std::size_t(offset);
  }
};

StreamNumbering stream_numbering(const BezierSurface& surface, const TessellationPlan& plan) {
  StreamNumbering numbering;
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
      numbering.corner[3 * p + std::size_t(k)] = it->second;
    }
  std::vector<PatchEdgePair> found;
  if (plan.shared.empty()) found = patch_adjacency(surface).pairs;
  for (const PatchEdgePair& pair : plan.shared.empty() ? found : plan.shared) {
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
  std::size_t next = numbering.corner_owner.size();
  for (const auto& [p, k] : numbering.edge_owner) {
    numbering.edge_offset.push_back(next);
    next += std::size_t(plan.edge[3 * std::size_t(p) + std::size_t(k)] - 1);
  }
  numbering.edge_offset.push_back(next);
  for (std::size_t p = 0; p < patches; ++p) {
    numbering.inner_offset.push_back(next);
    next += std::size_t(layout_of(plan, p).inner_points());
  }
  numbering.inner_offset.push_back(next);
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

std::size_t TessellationPlan::face_count() const {
  std::size_t faces = 0;
  for (std::size_t p = 0; p < inner.size(); ++p) faces += std::size_t(layout_of(*this, p).triangles());
  return faces;
}

TessellationPlan uniform_plan(const BezierSurface& surface, int density) {
  check_density(density);
  return {std::vector<int>(surface.patches.size(), density), std::vector<int>(3 * surface.patches.size(), density), {}};
}

TessellationPlan plan_from_densities(const BezierSurface& surface, std::vector<int> density) {
  if (density.size() != surface.patches.size())
    throw InvalidInput("a tessellation needs one density per patch");
  for (const int n : density) check_density(n);
  TessellationPlan plan;
  plan.edge.resize(3 * density.size());
  for (std::size_t i = 0; i < plan.edge.size(); ++i) plan.edge[i] = density[i / 3];
  plan.shared = patch_adjacency(surface).pairs;
  for (const PatchEdgePair& pair : plan.shared) {
    int& a = plan.edge[3 * std::size_t(pair.patch_a) + std::size_t(pair.edge_a)];
    int& b = plan.edge[3 * std::size_t(pair.patch_b) + std::size_t(pair.edge_b)];
    a = b = std::max(a, b);
  }
  plan.inner = std::move(density);
  return plan;
}

void write_tessellation_ply(const BezierSurface& surface, const TessellationPlan& plan,
                            const std::filesystem::path& path, io::Overwrite overwrite) {
  static_assert(std::endian::native == std::endian::little, "the PLY is written in the machine's byte order");
  check_plan(surface, plan);
  const StreamNumbering numbering = stream_numbering(surface, plan);
  const std::size_t faces = plan.face_count();
  io::write_file_atomically_streamed(
      path,
      [&](const io::ByteSink& sink) {
        std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by scanstation smooth\n";
        // Appended piecewise: GCC 12 misreports a chained '+' here (-Wrestrict).
        out.append("element vertex ").append(std::to_string(numbering.vertices()));
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
          append_vertex(out, patch_corner(surface.patches[std::size_t(p)], k),
                        unit_normal(surface.patches[std::size_t(p)], Barycentric::Unit(k)));
          flush_if_full();
        }
        for (const auto& [p, k] : numbering.edge_owner) {
          const CubicTriangle& patch = surface.patches[std::size_t(p)];
          const int n = plan.edge[3 * std::size_t(p) + std::size_t(k)];
          for (int step = 1; step < n; ++step) {
            const auto [a, b] = grid_of_edge(k, step, n);
            append_vertex(out, edge_point(patch, k, step, n), unit_normal(patch, grid_parameter(a, b, n)));
            flush_if_full();
          }
        }
        for (std::size_t p = 0; p < surface.patches.size(); ++p) {
          const PatchLayout layout = layout_of(plan, p);
          const int m = layout.m();
          for (int a = 1; a < m; ++a)
            for (int b = 1; a + b < m; ++b) {
              const Barycentric uvw = grid_parameter(a, b, m);
              append_vertex(out, evaluate(surface.patches[p], uvw), unit_normal(surface.patches[p], uvw));
              flush_if_full();
            }
        }
        for (std::size_t p = 0; p < surface.patches.size(); ++p) {
          const PatchLayout layout = layout_of(plan, p);
          layout.for_each_triangle([&](int i, int j, int k) {
            const unsigned char three = 3;
            const std::int32_t index[3] = {std::int32_t(numbering.global(int(p), layout, i)),
                                           std::int32_t(numbering.global(int(p), layout, j)),
                                           std::int32_t(numbering.global(int(p), layout, k))};
            append_raw(out, &three, 1);
            append_raw(out, index, sizeof index);
          });
          flush_if_full();
        }
        sink(out);
      },
      overwrite);
}

void write_tessellation_ply(const BezierSurface& surface, int density, const std::filesystem::path& path,
                            io::Overwrite overwrite) {
  write_tessellation_ply(surface, uniform_plan(surface, density), path, overwrite);
}

TriangleMesh tessellate(const BezierSurface& surface, const TessellationPlan& plan) {
  check_plan(surface, plan);
  std::unordered_map<Eigen::Vector3d, int, PositionHash, PositionEqual> index_of;
  std::vector<Eigen::Vector3d> positions, normals;
  std::vector<Eigen::Vector3i> faces;
  faces.reserve(plan.face_count());
  index_of.reserve(faces.capacity() / 2);
  std::vector<int> local;
  for (std::size_t p = 0; p < surface.patches.size(); ++p) {
    const CubicTriangle& patch = surface.patches[p];
    const PatchLayout layout = layout_of(plan, p);
    local.resize(std::size_t(layout.points()));
    for (int i = 0; i < layout.points(); ++i) {
      const Eigen::Vector3d x = local_position(patch, layout, i);
      const auto [it, inserted] = index_of.emplace(x, static_cast<int>(positions.size()));
      if (inserted) {
        positions.push_back(x);
        normals.push_back(unit_normal(patch, layout.parameter(i)));
      }
      local[std::size_t(i)] = it->second;
    }
    layout.for_each_triangle([&](int i, int j, int k) {
      faces.emplace_back(local[std::size_t(i)], local[std::size_t(j)], local[std::size_t(k)]);
    });
  }
  TriangleMesh mesh;
  mesh.vertices.positions.resize(static_cast<Eigen::Index>(positions.size()), 3);
  mesh.vertices.normals.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    mesh.vertices.positions.row(static_cast<Eigen::Index>(i)) = positions[i].transpose();
    mesh.vertices.normals.row(static_cast<Eigen::Index>(i)) = normals[i].transpose();
  }
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) mesh.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
  return mesh;
}

TriangleMesh tessellate(const BezierSurface& surface, int density) {
  return tessellate(surface, uniform_plan(surface, density));
}

}  // namespace scanstation
