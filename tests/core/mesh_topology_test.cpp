#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "sim/shapes.h"
#include "sim/random.h"
#include "test_support.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

namespace scanstation {
namespace {

Eigen::MatrixX3i without_face(const Eigen::MatrixX3i& F, Eigen::Index drop) {
  Eigen::MatrixX3i out(F.rows() - 1, 3);
  out << F.topRows(drop), F.bottomRows(F.rows() - drop - 1);
  return out;
}

TEST(MeshTopology, IcosphereIsAClosedOrientedGenusZeroManifold) {
  for (int s = 0; s <= 3; ++s) {
    const TriangleMesh sphere = sim::icosphere(s);
    const MeshTopology t = mesh_topology(sphere);
    EXPECT_TRUE(t.closed && t.manifold && t.oriented && t.orientable);
    EXPECT_EQ(t.genus, 0);
    EXPECT_EQ(t.components, 1u);
    EXPECT_EQ(t.euler_characteristic, 2);
    EXPECT_EQ(t.edges * 2, t.faces * 3);
  }
}

TEST(MeshTopology, TorusHasGenusOne) {
  const MeshTopology t = mesh_topology(sim::torus(2.0, 0.5, 16, 8));
  EXPECT_TRUE(t.closed && t.manifold && t.oriented);
  EXPECT_EQ(t.genus, 1);
  EXPECT_EQ(t.euler_characteristic, 0);
}

TEST(MeshTopology, RemovingFacesOpensBoundaryLoops) {
  const TriangleMesh sphere = sim::icosphere(2);
  Eigen::MatrixX3i F = without_face(sphere.faces, 0);
  MeshTopology t = mesh_topology(F, sphere.vertex_count());
  EXPECT_FALSE(t.closed);
  EXPECT_TRUE(t.manifold && t.oriented);
  EXPECT_EQ(t.boundary_edges, 3u);
  EXPECT_EQ(t.boundary_loops, 1u);
  EXPECT_EQ(t.genus, 0);  // a disc
  // A second hole far from the first: an annulus, still genus 0.
  F = without_face(F, F.rows() - 1);
  t = mesh_topology(F, sphere.vertex_count());
  EXPECT_EQ(t.boundary_loops, 2u);
  EXPECT_EQ(t.genus, 0);
}

TEST(MeshTopology, FlippedFaceIsOrientableButNotOriented) {
  TriangleMesh sphere = sim::icosphere(1);
  std::swap(sphere.faces(5, 0), sphere.faces(5, 1));
  const MeshTopology t = mesh_topology(sphere);
  EXPECT_TRUE(t.closed && t.manifold);
  EXPECT_FALSE(t.oriented);
  EXPECT_TRUE(t.orientable);
  EXPECT_EQ(t.genus, 0);
}

TEST(MeshTopology, MoebiusStripIsNotOrientable) {
  // A strip of 2n triangles whose ends are glued with a half twist.
  const int n = 6;
  Eigen::MatrixX3i F(2 * n, 3);
  // Vertices 0..n-1 on one rail, n..2n-1 on the other; the last quad joins
  // rail end (n-1, 2n-1) to the start crossed: (n, 0).
  for (int i = 0; i < n; ++i) {
    const int a = i, b = n + i;
    const int c = i + 1 < n ? i + 1 : n;      // crossed at the seam
    const int d = i + 1 < n ? n + i + 1 : 0;
    F.row(2 * i) << a, c, b;
    F.row(2 * i + 1) << c, d, b;
  }
  const MeshTopology t = mesh_topology(F, 2 * n);
  EXPECT_TRUE(t.manifold);
  EXPECT_FALSE(t.orientable);
  EXPECT_FALSE(t.genus.has_value());
  EXPECT_EQ(t.boundary_loops, 1u);
}

TEST(MeshTopology, NonManifoldEdgesAndVertices) {
  // Three triangles on the edge (0, 1).
  Eigen::MatrixX3i fin(3, 3);
  fin << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  MeshTopology t = mesh_topology(fin, 5);
  EXPECT_EQ(t.non_manifold_edges, 1u);
  EXPECT_FALSE(t.manifold);
  EXPECT_FALSE(t.genus.has_value());
  // Two tetrahedra touching at one vertex: closed, but the shared vertex has two fans.
  Eigen::MatrixX3i bowtie(8, 3);
  bowtie << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3,  //
      0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6;
  t = mesh_topology(bowtie, 7);
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.non_manifold_vertices, 1u);
  EXPECT_FALSE(t.manifold);
  EXPECT_EQ(t.components, 1u);
}

TEST(MeshTopology, DegenerateDuplicateAndIsolated) {
  Eigen::MatrixX3i F(3, 3);
  F << 0, 1, 2, 2, 1, 0, 3, 3, 1;
  const MeshTopology t = mesh_topology(F, 6);
  EXPECT_EQ(t.degenerate_faces, 1u);
  EXPECT_EQ(t.duplicate_faces, 1u);
  EXPECT_EQ(t.isolated_vertices, 2u);
  EXPECT_FALSE(t.manifold);
  EXPECT_THROW(mesh_topology(F, 3), InvalidInput);
}

// Genus of real closed meshes from Debian's libcgal-demo: the tori as their
// names say; the elephant has three handles (χ = 2775 − 8337 + 5558 = −4).
// The counts by their definitions, with maps and sets (quadratic at worst),
// against mesh_topology's sorted passes, on random triangle soups over a few
// vertices: non-manifold edges and vertices, duplicates and degenerate faces
// are everywhere there.
struct Counts {
  std::size_t edges = 0, boundary_edges = 0, non_manifold_edges = 0, non_manifold_vertices = 0, duplicate_faces = 0,
              degenerate_faces = 0;
};
Counts counts_by_definition(const Eigen::MatrixX3i& F, int vertices) {
  Counts c;
  std::map<std::pair<int, int>, int> faces_at_edge;
  std::set<std::array<int, 3>> seen;
  std::vector<std::vector<int>> faces_at(static_cast<std::size_t>(vertices));
  for (int f = 0; f < F.rows(); ++f) {
    std::array<int, 3> v{F(f, 0), F(f, 1), F(f, 2)};
    for (int k = 0; k < 3; ++k) {
      const int a = v[static_cast<std::size_t>(k)], b = v[static_cast<std::size_t>((k + 1) % 3)];
      if (a != b) ++faces_at_edge[{std::min(a, b), std::max(a, b)}];
      faces_at[static_cast<std::size_t>(a)].push_back(f);
    }
    std::sort(v.begin(), v.end());
    c.degenerate_faces += v[0] == v[1] || v[1] == v[2];
    c.duplicate_faces += !seen.insert(v).second;
  }
  for (const auto& [edge, n] : faces_at_edge) {
    ++c.edges;
    c.boundary_edges += n == 1;
    c.non_manifold_edges += n > 2;
  }
  // The points next to v in face f: the corners' neighbours (v itself too
  // where f repeats v).
  const auto next_to = [&](int f, int v) {
    std::set<int> out;
    for (int k = 0; k < 3; ++k)
      if (F(f, k) == v) out.insert({F(f, (k + 1) % 3), F(f, (k + 2) % 3)});
    return out;
  };
  for (int v = 0; v < vertices; ++v) {  // fans: faces at v joined through an edge (v, w) they both have
    std::vector<int> fs = faces_at[static_cast<std::size_t>(v)];
    std::sort(fs.begin(), fs.end());
    fs.erase(std::unique(fs.begin(), fs.end()), fs.end());
    if (fs.empty()) continue;
    std::vector<int> fan(fs.size(), -1);
    int fans = 0;
    for (std::size_t seed = 0; seed < fs.size(); ++seed) {
      if (fan[seed] >= 0) continue;
      ++fans;
      std::vector<std::size_t> stack{seed};
      fan[seed] = fans;
      while (!stack.empty()) {
        const int f = fs[stack.back()];
        stack.pop_back();
        for (std::size_t g = 0; g < fs.size(); ++g) {
          if (fan[g] >= 0) continue;
          bool shared = false;
          for (const int w : next_to(f, v)) shared = shared || next_to(fs[g], v).count(w) > 0;
          if (shared) {
            fan[g] = fans;
            stack.push_back(g);
          }
        }
      }
    }
    c.non_manifold_vertices += fans > 1;
  }
  return c;
}

TEST(MeshTopology, SortedPassesAgreeWithTheDefinitionsOnRandomSoups) {
  sim::Random random(12);
  for (int trial = 0; trial < 200; ++trial) {
    const int vertices = 4 + trial % 12;
    Eigen::MatrixX3i F(1 + trial % 40, 3);
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) F(f, k) = std::min(vertices - 1, static_cast<int>(random.uniform() * vertices));
    const MeshTopology t = mesh_topology(F, vertices);
    const Counts c = counts_by_definition(F, vertices);
    EXPECT_EQ(t.edges, c.edges) << "trial " << trial;
    EXPECT_EQ(t.boundary_edges, c.boundary_edges) << "trial " << trial;
    EXPECT_EQ(t.non_manifold_edges, c.non_manifold_edges) << "trial " << trial;
    EXPECT_EQ(t.non_manifold_vertices, c.non_manifold_vertices) << "trial " << trial;
    EXPECT_EQ(t.duplicate_faces, c.duplicate_faces) << "trial " << trial;
    EXPECT_EQ(t.degenerate_faces, c.degenerate_faces) << "trial " << trial;
  }
}

TEST(MeshTopology, RealMeshesHaveTheirKnownGenus) {
  const std::vector<std::pair<std::string, int>> expected = {
      {"meshes/elephant.off", 3}, {"meshes/sphere.off", 0},    {"meshes/double-torus-example.off", 2},
      {"meshes/3torus.off", 3},   {"meshes/bunny00.off", 0}, {"meshes/triceratops.off", 0}};
  for (const auto& [file, genus] : expected) {
    const TriangleMesh mesh = io::read_mesh(test::cgal_data(file));
    const MeshTopology t = mesh_topology(mesh);
    EXPECT_TRUE(t.closed) << file;
    EXPECT_TRUE(t.manifold) << file;
    EXPECT_EQ(t.genus, genus) << file;
  }
  const MeshTopology open = mesh_topology(io::read_mesh(test::cgal_data("meshes/elephant-with-holes.off")));
  EXPECT_FALSE(open.closed);
  EXPECT_GT(open.boundary_loops, 0u);
}

}  // namespace
}  // namespace scanstation
