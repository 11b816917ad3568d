// 3D flintstone approximations never crack (thesis §7.3.2: side splits are
// shared by both triangles of a side): every level and every adaptive
// approximation of a closed genus-0 mesh is itself closed.
#include "core/io/mesh_io.h"
#include "reconstruct/flintstone_approximation.h"
#include "reconstruct/flintstone_tree3.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <algorithm>

namespace scanstation {
namespace {

/// Counts of the undirected edges not shared by exactly two triangles, and of
/// directed edges used twice (two triangles of the same orientation).
struct EdgeDefects {
  int open = 0;       ///< one triangle
  int crowded = 0;    ///< three or more triangles
  int misoriented = 0;
};

EdgeDefects edge_defects(const Eigen::MatrixX3i& F) {
  std::vector<std::pair<std::pair<int, int>, bool>> uses;  // (min, max), used as min→max
  uses.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      uses.push_back({{std::min(a, b), std::max(a, b)}, a < b});
    }
  std::sort(uses.begin(), uses.end());
  EdgeDefects defects;
  for (std::size_t first = 0; first < uses.size();) {
    std::size_t last = first, forward = 0;
    for (; last < uses.size() && uses[last].first == uses[first].first; ++last) forward += uses[last].second;
    const std::size_t total = last - first;
    defects.open += total == 1;
    defects.crowded += total > 2;
    defects.misoriented += total == 2 && forward != 1;
    first = last;
  }
  return defects;
}

void expect_closed(const Eigen::MatrixX3i& F, const std::string& what) {
  const EdgeDefects defects = edge_defects(F);
  EXPECT_GT(F.rows(), 0) << what;
  EXPECT_EQ(defects.open, 0) << what << " (" << F.rows() << " triangles)";
  EXPECT_EQ(defects.crowded, 0) << what;
  EXPECT_EQ(defects.misoriented, 0) << what;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    EXPECT_TRUE(F(f, 0) != F(f, 1) && F(f, 1) != F(f, 2) && F(f, 2) != F(f, 0)) << what << ": degenerate triangle";
}

/// V − E + F of a closed mesh (E = 3F/2 when every edge has two triangles).
Eigen::Index euler_characteristic(const Eigen::MatrixX3i& F) {
  std::vector<int> used(F.data(), F.data() + F.size());
  std::sort(used.begin(), used.end());
  const auto vertices = static_cast<Eigen::Index>(std::unique(used.begin(), used.end()) - used.begin());
  return vertices - F.rows() * 3 / 2 + F.rows();
}

/// The plain corner triangles v_p v_s v_t of the approximating nodes (void
/// ones left out): what the approximation was before it was stitched.
Eigen::MatrixX3i corner_triangles(const FlintstoneTree3& tree, const MeshApproximation& a) {
  std::vector<std::array<int, 3>> corners;
  for (const int id : a.nodes) {
    const auto c = tree.nodes[static_cast<std::size_t>(id)].corners;
    if (c[0] != c[1] && c[1] != c[2] && c[2] != c[0]) corners.push_back(c);
  }
  Eigen::MatrixX3i F(static_cast<Eigen::Index>(corners.size()), 3);
  for (std::size_t k = 0; k < corners.size(); ++k) F.row(static_cast<Eigen::Index>(k)) << corners[k][0], corners[k][1], corners[k][2];
  return F;
}

/// Every level and the adaptive approximation at several bounds is closed
/// and has the mesh's Euler characteristic; the finest level is still the
/// original mesh.
void expect_every_approximation_closed(const TriangleMesh& mesh, const std::string& name) {
  const FlintstoneTree3 tree = flintstone_tree(mesh);
  int open_corner_triangles = 0, open_stitched = 0, other_topology = 0;
  const Eigen::Index euler = euler_characteristic(mesh.faces);
  for (int level = 0; level < tree.levels(); ++level) {
    const MeshApproximation a = approximation(tree, level);
    const Eigen::MatrixX3i corners = corner_triangles(tree, a);
    const int open_corners = edge_defects(corners).open, open = edge_defects(a.faces).open;
    open_corner_triangles += open_corners;
    open_stitched += open;
    expect_closed(a.faces, name + " level " + std::to_string(level));
    other_topology += euler_characteristic(a.faces) != euler;
    if (level == 10)
      std::printf("%s level 10: %lld triangles, %d open edges; corner triangles only: %lld, %d open\n", name.c_str(),
                  static_cast<long long>(a.faces.rows()), open, static_cast<long long>(corners.rows()), open_corners);
  }
  EXPECT_EQ(approximation(tree, tree.levels() - 1).faces.rows(), mesh.face_count()) << name;
  const double size = (mesh.vertices.positions.colwise().maxCoeff() - mesh.vertices.positions.colwise().minCoeff()).norm();
  for (const double bound : {0.3, 0.1, 0.03, 0.01, 0.003}) {
    const MeshApproximation a = adaptive_approximation(tree, bound * size);
    EXPECT_LE(a.errors.e5, bound * size) << name;
    open_corner_triangles += edge_defects(corner_triangles(tree, a)).open;
    open_stitched += edge_defects(a.faces).open;
    expect_closed(a.faces, name + " adaptive " + std::to_string(bound));
    other_topology += euler_characteristic(a.faces) != euler;
  }
  std::printf("%s: %d levels; open edges summed over all levels and bounds: %d stitched, %d corner triangles only; "
              "%d approximations with another Euler characteristic than the mesh\n",
              name.c_str(), tree.levels(), open_stitched, open_corner_triangles, other_topology);
  EXPECT_EQ(other_topology, 0) << name << ": approximations that are no longer spheres";
}

TEST(FlintstoneClosed3, Icospheres) {
  expect_every_approximation_closed(sim::icosphere(4), "icosphere(4)");
  expect_every_approximation_closed(sim::icosphere(5), "icosphere(5)");
}

TEST(FlintstoneClosed3, Ellipsoid) {
  expect_every_approximation_closed(sim::ellipsoid({3.0, 2.0, 1.0}, 4), "ellipsoid");
}

TEST(FlintstoneClosed3, RealMeshes) {
  for (const std::string name : {"bunny00.off", "cactus.off", "cow.off", "dino.off"})
    expect_every_approximation_closed(io::read_mesh(test::cgal_data("meshes/" + name)), name);
}

}  // namespace
}  // namespace scanstation
