// 3D flintstones (thesis §7.3): tree invariants on generated and real
// meshes, approximations, exact point inclusion against brute force.
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "reconstruct/flintstone_approximation.h"
#include "reconstruct/flintstone_inclusion.h"
#include "reconstruct/flintstone_tree3.h"
#include "sim/random.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <Eigen/Geometry>
#include <set>

namespace scanstation {
namespace {

std::array<int, 3> rotated_to_smallest(int a, int b, int c) {
  if (a < b && a < c) return {a, b, c};
  if (b < a && b < c) return {b, c, a};
  return {c, a, b};
}

std::multiset<std::array<int, 3>> face_set(const Eigen::MatrixX3i& F) {
  std::multiset<std::array<int, 3>> set;
  for (Eigen::Index f = 0; f < F.rows(); ++f) set.insert(rotated_to_smallest(F(f, 0), F(f, 1), F(f, 2)));
  return set;
}

/// Children partition their parent's faces, the leaves are the original faces
/// once each, and every vertex of a node's faces lies in its flintstone (so in
/// all its ancestors' flintstones).
void expect_valid_tree(const FlintstoneTree3& tree, const std::string& what) {
  const auto point = [&](int v) { return Eigen::Vector3d(tree.vertices.row(v).transpose()); };
  std::vector<int> leaf_faces;
  std::size_t outside = 0;
  for (const int id : tree.reachable()) {
    const FlintstoneNode3& node = tree.nodes[static_cast<std::size_t>(id)];
    for (int k = 0; k < node.face_count; ++k)
      for (int j = 0; j < 3; ++j)
        outside += !node.stone.contains(point(tree.faces(tree.face_order[static_cast<std::size_t>(node.first_face + k)], j)));
    if (node.leaf()) {
      EXPECT_EQ(node.face_count, 1) << what;
      leaf_faces.push_back(tree.face_order[static_cast<std::size_t>(node.first_face)]);
      continue;
    }
    EXPECT_GE(node.child_count, 2) << what;
    int covered = 0;
    for (int c = 0; c < node.child_count; ++c) {
      const FlintstoneNode3& child = tree.nodes[static_cast<std::size_t>(node.first_child + c)];
      EXPECT_EQ(child.first_face, node.first_face + covered) << what;
      EXPECT_EQ(child.depth, node.depth + 1) << what;
      EXPECT_GT(child.face_count, 0) << what;
      covered += child.face_count;
    }
    EXPECT_EQ(covered, node.face_count) << what;
  }
  EXPECT_EQ(outside, 0u) << what << ": vertices outside their flintstones";
  std::sort(leaf_faces.begin(), leaf_faces.end());
  ASSERT_EQ(static_cast<Eigen::Index>(leaf_faces.size()), tree.faces.rows()) << what;
  for (std::size_t k = 0; k < leaf_faces.size(); ++k) EXPECT_EQ(leaf_faces[k], static_cast<int>(k)) << what;
  // The finest approximation is the original mesh, orientation included.
  const MeshApproximation finest = approximation(tree, tree.levels() - 1);
  EXPECT_EQ(face_set(finest.faces), face_set(tree.faces)) << what;
  EXPECT_EQ(finest.errors.e1, 0.0) << what;
}

/// Query points: uniform in the box, at vertices, on faces, and just off them.
std::vector<Eigen::Vector3d> queries_near(const TriangleMesh& mesh, int count, std::uint64_t seed) {
  sim::Random random(seed);
  const Eigen::MatrixX3d& V = mesh.vertices.positions;
  const Eigen::Vector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  const double size = (hi - lo).norm();
  std::vector<Eigen::Vector3d> queries;
  for (int k = 0; k < count; ++k) {
    const Eigen::Index f = static_cast<Eigen::Index>(random.below(static_cast<std::uint64_t>(mesh.face_count())));
    const Eigen::Vector3d a = V.row(mesh.faces(f, 0)), b = V.row(mesh.faces(f, 1)), c = V.row(mesh.faces(f, 2));
    double u = random.uniform(), v = random.uniform();
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Eigen::Vector3d on = a + u * (b - a) + v * (c - a);
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    switch (k % 7) {
      case 0: queries.push_back(lo + (hi - lo).cwiseProduct(Eigen::Vector3d(random.uniform(), random.uniform(), random.uniform()))); break;
      case 1: queries.push_back(a); break;
      case 2: queries.push_back(on); break;
      case 3: queries.push_back(on + 1e-12 * size * random.normal() * normal); break;
      case 4: queries.push_back(0.5 * (a + b) + 1e-9 * size * random.normal() * normal); break;
      case 5: {  // straight above or beside a vertex: the axis ray passes through it
        Eigen::Vector3d x = a;
        x[static_cast<Eigen::Index>(random.below(3))] += 0.1 * size * random.normal();
        queries.push_back(x);
        break;
      }
      default: queries.push_back(on + 1e-2 * size * random.normal() * normal); break;
    }
  }
  return queries;
}

void expect_inclusion_matches_brute_force(const FlintstoneTree3& tree, const TriangleMesh& mesh, int count,
                                          const std::string& what) {
  int disagreements = 0, index_disagreements = 0, inside_count = 0;
  InclusionStats stats, index_stats;
  const FlintstoneInclusion3 index = inclusion_index(tree);
  for (const Eigen::Vector3d& x : queries_near(mesh, count, 17)) {
    const bool expected = inside_brute_force(mesh.vertices.positions, mesh.faces, x);
    inside_count += expected;
    disagreements += inside(tree, x, &stats) != expected;
    index_disagreements += inside(index, x, &index_stats) != expected;
  }
  EXPECT_EQ(disagreements, 0) << what;
  EXPECT_EQ(index_disagreements, 0) << what << ": packed index";
  EXPECT_GT(stats.replacements, 0u) << what << ": Lemma 6.1 never used";
  EXPECT_GT(index_stats.replacements, 0u) << what << ": Lemma 6.1 never used by the packed index";
  // The packed index tests fewer flintstones than the tree (chains collapsed,
  // and only where a fan could replace the node's faces).
  EXPECT_LT(index_stats.flintstone_tests, stats.flintstone_tests) << what;
  if (mesh.face_count() >= 1000) {  // hierarchy pays: a small share of the brute-force tests
    EXPECT_LT(stats.crossing_tests, static_cast<std::size_t>(count * mesh.face_count()) / 20) << what;
  }
  EXPECT_GT(inside_count, count / 10) << what;
  EXPECT_LT(inside_count, count) << what;
}

TriangleMesh scaled(TriangleMesh mesh, double scale, const Eigen::Vector3d& offset) {
  mesh.vertices.positions = (mesh.vertices.positions * scale).rowwise() + offset.transpose();
  return mesh;
}

TEST(FlintstoneTree3, GeneratedShapesAtAnyScale) {
  for (const double scale : {1.0, 1e-8, 1e8}) {
    const TriangleMesh mesh = scaled(sim::ellipsoid({3.0, 2.0, 1.0}, 3), scale, Eigen::Vector3d(5, -7, 1e3) * scale);
    const std::string what = "ellipsoid scale " + std::to_string(scale);
    const FlintstoneTree3 tree = flintstone_tree(mesh);
    expect_valid_tree(tree, what);
    expect_inclusion_matches_brute_force(tree, mesh, 1200, what);
  }
  // Beyond the balls' range: named, not "all vertices coincide".
  test::expect_error<InvalidInput>([] { flintstone_tree(scaled(sim::icosphere(1), 1e200, Eigen::Vector3d::Zero())); },
                                   {"mesh's coordinates reach 1e+200", "scale it first"});
  test::expect_error<InvalidInput>([] { flintstone_tree(scaled(sim::icosphere(1), 1e-200, Eigen::Vector3d::Zero())); },
                                   {"mesh spans only 2e-200", "scale it first"});
  for (const double threshold : {0.0, 0.6}) {
    const TriangleMesh mesh = sim::icosphere(3);
    const FlintstoneTree3 tree = flintstone_tree(mesh, {threshold});
    expect_valid_tree(tree, "icosphere threshold " + std::to_string(threshold));
    EXPECT_GT(tree.stats.three_splits, 0u);
    if (threshold > 0.0) {
      EXPECT_GT(tree.stats.side_splits, 0u);
    }
  }
}

TEST(FlintstoneTree3, RealMeshes) {
  for (const std::string name : {"cube.off", "cactus.off", "elephant.off"}) {
    const TriangleMesh mesh = io::read_mesh(test::cgal_data("meshes/" + name));
    const FlintstoneTree3 tree = flintstone_tree(mesh);
    expect_valid_tree(tree, name);
    expect_inclusion_matches_brute_force(tree, mesh, name == "elephant.off" ? 600 : 1500, name);
    // Storage Θ(N_t) (Theorem 7.4): fewer than two nodes per face.
    EXPECT_LT(tree.nodes.size(), 2 * static_cast<std::size_t>(mesh.face_count())) << name;
  }
}

TEST(FlintstoneInclusion3, PackedIndexAnswersAsTheTree) {
  // Many queries, no brute force: the packed index (collapsed chains, box
  // pruning, axis ray) must answer exactly what the tree answers.
  for (const std::string name : {"cube.off", "cactus.off", "elephant.off", "armadillo.off"}) {
    const TriangleMesh mesh = io::read_mesh(test::cgal_data("meshes/" + name));
    const FlintstoneTree3 tree = flintstone_tree(mesh);
    const FlintstoneInclusion3 index = inclusion_index(tree);
    ASSERT_TRUE(index.box.isApprox(tree.root().box, 0.0)) << name;
    EXPECT_TRUE(index.nodes.front().box().contains(index.box)) << name;
    // Chains collapsed: fewer nodes than the tree, apart from the sorting
    // nodes above many children, whose boxes hold their children's.
    std::size_t sorting = 0, unheld = 0;
    for (int k = 0; k < static_cast<int>(index.nodes.size()); ++k) {
      if (index.lens_of[static_cast<std::size_t>(k)] != FlintstoneInclusion3::sorting_node) continue;
      ++sorting;
      const auto& node = index.nodes[static_cast<std::size_t>(k)];
      EXPECT_EQ(index.triangle_count(k), 0) << name;  // no fan: always refined
      for (int c = k + 1; c < node.skip; c = index.nodes[static_cast<std::size_t>(c)].skip)
        unheld += !node.box().contains(index.nodes[static_cast<std::size_t>(c)].box());
    }
    EXPECT_EQ(unheld, 0u) << name;
    EXPECT_LE(index.nodes.size() - sorting, tree.nodes.size()) << name;
    // The float boxes, rounded outwards, hold their triangles exactly.
    std::size_t loose = 0, fans = 0;
    for (int k = 0; k < static_cast<int>(index.nodes.size()); ++k) {
      const auto& node = index.nodes[static_cast<std::size_t>(k)];
      const int count = index.triangle_count(k);
      fans += !node.leaf(k) && count > 0;
      for (int t = node.first_triangle; t < node.first_triangle + count; ++t)
        for (const Eigen::Vector3d& corner : index.triangles[static_cast<std::size_t>(t)]) loose += !node.box().contains(corner);
    }
    EXPECT_EQ(loose, 0u) << name;
    EXPECT_GT(fans, 0u) << name;
    EXPECT_GT(index.storage_bytes(), 0u) << name;
    int disagreements = 0, inside_count = 0;
    const std::vector<Eigen::Vector3d> queries = queries_near(mesh, 6000, 23);
    for (const Eigen::Vector3d& x : queries) {
      const bool expected = inside(tree, x);
      inside_count += expected;
      disagreements += inside(index, x) != expected;
    }
    EXPECT_EQ(disagreements, 0) << name;
    EXPECT_GT(inside_count, 600) << name;
    EXPECT_LT(inside_count, 6000) << name;
  }
}

TEST(FlintstoneApproximation3, AdaptiveStaysWithinTheBound) {
  const TriangleMesh mesh = io::read_mesh(test::cgal_data("meshes/cactus.off"));
  const FlintstoneTree3 tree = flintstone_tree(mesh);
  const double size = (mesh.vertices.positions.colwise().maxCoeff() - mesh.vertices.positions.colwise().minCoeff()).norm();
  Eigen::Index previous = 0;
  for (const double bound : {0.2, 0.05, 0.01}) {
    const MeshApproximation a = adaptive_approximation(tree, bound * size);
    EXPECT_LE(a.errors.e5, bound * size);
    EXPECT_LE(a.errors.e2, a.errors.e1 * (1 + 1e-12) + 1e-12);
    EXPECT_GE(a.faces.rows(), previous);
    EXPECT_LT(a.faces.rows(), mesh.face_count());
    previous = a.faces.rows();
  }
  EXPECT_EQ(approximation(tree, 0).faces.rows(), 2);  // the root triangle, once per side
}

TEST(FlintstoneTree3, DynamicInsertionRebuildsASubtree) {
  TriangleMesh mesh = io::read_mesh(test::cgal_data("meshes/cactus.off"));
  FlintstoneTree3 tree = flintstone_tree(mesh);
  sim::Random random(5);
  int local = 0;
  for (int step = 0; step < 40; ++step) {
    const int face = static_cast<int>(random.below(static_cast<std::uint64_t>(tree.faces.rows())));
    const auto corner = [&](int k) { return Eigen::Vector3d(tree.vertices.row(tree.faces(face, k))); };
    const Eigen::Vector3d normal = (corner(1) - corner(0)).cross(corner(2) - corner(0)).normalized();
    const double push = step % 10 == 9 ? 0.05 : 1e-4 * random.normal();  // sometimes well off the surface
    const Eigen::Vector3d x = (corner(0) + corner(1) + corner(2)) / 3.0 + push * normal;
    const int before = static_cast<int>(tree.faces.rows());
    const int rebuilt = insert_vertex(tree, face, x);
    ASSERT_EQ(tree.faces.rows(), before + 2);
    EXPECT_GE(rebuilt, 3);
    local += rebuilt < before / 2;
  }
  EXPECT_GT(local, 20) << "most insertions should rebuild a small subtree";
  mesh.vertices.positions = tree.vertices;
  mesh.faces = tree.faces;
  expect_valid_tree(tree, "after insertions");
  expect_inclusion_matches_brute_force(tree, mesh, 1500, "after insertions");
}

TEST(FlintstoneTree3, IsolatedVerticesAreNotCorners) {
  TriangleMesh mesh = sim::icosphere(2);
  mesh.vertices.positions.conservativeResize(mesh.vertex_count() + 1, 3);
  mesh.vertices.positions.bottomRows(1) << 40.0, 0.0, 0.0;  // far away, in no face
  const FlintstoneTree3 tree = flintstone_tree(mesh);
  for (const int corner : tree.root().corners) EXPECT_LT(corner, mesh.vertex_count() - 1);
  // The same splits as without the isolated vertex.
  const FlintstoneTree3 plain = flintstone_tree(sim::icosphere(2));
  EXPECT_EQ(tree.root().corners, plain.root().corners);
  EXPECT_EQ(tree.nodes.size(), plain.nodes.size());
  expect_valid_tree(tree, "icosphere with an isolated vertex");
  expect_inclusion_matches_brute_force(tree, mesh, 600, "icosphere with an isolated vertex");
}

TEST(FlintstoneTree3, RejectsOpenMeshes) {
  TriangleMesh open = sim::icosphere(1);
  open.faces.conservativeResize(open.faces.rows() - 1, 3);
  test::expect_error<TopologyError>([&] { flintstone_tree(open); }, {"not closed"});
  test::expect_error<InvalidInput>([] { flintstone_tree(TriangleMesh{}); }, {"no faces"});
}

// Two closed surfaces, apart or sharing one vertex, are closed and oriented
// edge by edge, but the root's cut paths cannot split them in two: the
// refinement ran past its faces (a crash) before they were refused.
TEST(FlintstoneTree3, RejectsSeveralPartsAndPinchedVertices) {
  const TriangleMesh ball = sim::icosphere(1);
  const auto two = [&](const Eigen::RowVector3d& offset, bool share_vertex) {
    TriangleMesh mesh = ball;
    const Eigen::Index n = ball.vertex_count();
    mesh.vertices.positions.conservativeResize(2 * n, 3);
    mesh.vertices.positions.bottomRows(n) = ball.vertices.positions.rowwise() + offset;
    mesh.faces.conservativeResize(2 * ball.face_count(), 3);
    mesh.faces.bottomRows(ball.face_count()) = ball.faces.array() + static_cast<int>(n);
    if (share_vertex) {  // the second ball's vertex 0 becomes the first's vertex 0
      const Eigen::RowVector3d shift = ball.vertices.positions.row(0) - mesh.vertices.positions.row(n);
      mesh.vertices.positions.bottomRows(n).rowwise() += shift;
      for (Eigen::Index f = ball.face_count(); f < mesh.face_count(); ++f)
        for (int k = 0; k < 3; ++k)
          if (mesh.faces(f, k) == n) mesh.faces(f, k) = 0;
    }
    return mesh;
  };
  test::expect_error<TopologyError>([&] { flintstone_tree(two({3, 0, 0}, false)); }, {"2 separate parts"});
  const TriangleMesh pinched = two(-2 * ball.vertices.positions.row(0), true);
  test::expect_error<TopologyError>([&] { flintstone_tree(pinched); }, {"1 vertex joins several fans"});
}

}  // namespace
}  // namespace scanstation
