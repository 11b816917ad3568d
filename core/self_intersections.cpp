#include "core/self_intersections.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <future>
#include <iterator>
#include <utility>
#include <vector>

namespace scanstation {

namespace {
// Below this many faces one pass on one core.
constexpr Eigen::Index kSplitFaces = 4096;
}  // namespace

std::optional<std::size_t> self_intersections(const TriangleMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  using Face = Mesh::Face_index;
  Mesh sm;
  std::vector<Mesh::Vertex_index> vertex;
  vertex.reserve(static_cast<std::size_t>(mesh.vertex_count()));
  const auto& P = mesh.vertices.positions;
  for (Eigen::Index i = 0; i < P.rows(); ++i) vertex.push_back(sm.add_vertex(Kernel::Point_3(P(i, 0), P(i, 1), P(i, 2))));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const auto face = sm.add_face(vertex[static_cast<std::size_t>(mesh.faces(f, 0))],
                                  vertex[static_cast<std::size_t>(mesh.faces(f, 1))],
                                  vertex[static_cast<std::size_t>(mesh.faces(f, 2))]);
    if (face == Mesh::null_face()) return std::nullopt;
  }
  std::vector<std::pair<Face, Face>> pairs;
  if (mesh.face_count() < kSplitFaces) {
    CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
    return pairs.size();
  }
  // Both cores: the faces split by a plane x = s into those reaching s or
  // below and those reaching s or above (a face across the plane is in
  // both). A face wholly below and one wholly above have disjoint boxes, so
  // they cannot meet: every pair that can is within one half, and a pair of
  // faces across the plane is found in both (counted once). The halves'
  // checks only read the mesh.
  std::vector<std::pair<double, double>> x(static_cast<std::size_t>(mesh.face_count()));  // each face's x extent
  std::vector<double> middle(x.size());
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const double a = P(mesh.faces(f, 0), 0), b = P(mesh.faces(f, 1), 0), c = P(mesh.faces(f, 2), 0);
    x[static_cast<std::size_t>(f)] = {std::min({a, b, c}), std::max({a, b, c})};
    middle[static_cast<std::size_t>(f)] = 0.5 * (x[static_cast<std::size_t>(f)].first + x[static_cast<std::size_t>(f)].second);
  }
  const auto median = middle.begin() + static_cast<std::ptrdiff_t>(middle.size() / 2);
  std::nth_element(middle.begin(), median, middle.end());
  const double s = *median;
  std::vector<Face> below, above;
  for (std::size_t f = 0; f < x.size(); ++f) {
    if (x[f].first <= s) below.push_back(Face(static_cast<Mesh::size_type>(f)));
    if (x[f].second >= s) above.push_back(Face(static_cast<Mesh::size_type>(f)));
  }
  auto other = std::async(std::launch::async, [&] {
    std::vector<std::pair<Face, Face>> found;
    CGAL::Polygon_mesh_processing::self_intersections(below, sm, std::back_inserter(found));
    return found;
  });
  CGAL::Polygon_mesh_processing::self_intersections(above, sm, std::back_inserter(pairs));
  const std::vector<std::pair<Face, Face>> found = other.get();
  pairs.insert(pairs.end(), found.begin(), found.end());
  for (auto& [a, b] : pairs)
    if (b < a) std::swap(a, b);
  std::sort(pairs.begin(), pairs.end());
  return static_cast<std::size_t>(std::unique(pairs.begin(), pairs.end()) - pairs.begin());
}

}  // namespace scanstation
