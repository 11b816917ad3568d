#include "core/self_intersections.h"

#include "core/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <future>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace scanstation {

namespace {
// Below this many faces one pass on one core.
constexpr Eigen::Index kSplitFaces = 4096;
}  // namespace

std::optional<std::size_t> self_intersections(const TriangleMesh& mesh, const std::vector<char>& meet_properly) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  using Face = Mesh::Face_index;
  if (!meet_properly.empty() && meet_properly.size() != static_cast<std::size_t>(mesh.face_count()))
    throw InvalidInput("self_intersections: " + std::to_string(meet_properly.size()) + " face flags for " +
                       std::to_string(mesh.face_count()) + " faces");
  if (!meet_properly.empty() && std::find(meet_properly.begin(), meet_properly.end(), 0) == meet_properly.end())
    return 0;
  const auto& P = mesh.vertices.positions;
  const auto box = [&](Eigen::Index f) {
    CGAL::Bbox_3 b;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces(f, k);
      b += Kernel::Point_3(P(v, 0), P(v, 1), P(v, 2)).bbox();
    }
    return b;
  };
  // The faces that take part: all, or those whose boxes meet an unflagged
  // face's (closed boxes, so its neighbours too). A pair that meets wrongly
  // holds an unflagged face, and then both of its faces are here.
  std::vector<Face> faces;
  if (meet_properly.empty()) {
    for (Eigen::Index f = 0; f < mesh.face_count(); ++f) faces.push_back(Face(static_cast<Mesh::size_type>(f)));
  } else {
    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Eigen::Index>;
    std::vector<Box> open, all;
    all.reserve(meet_properly.size());
    for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
      all.emplace_back(box(f), f);
      if (!meet_properly[static_cast<std::size_t>(f)]) open.push_back(all.back());
    }
    std::vector<char> taking_part(meet_properly.size(), 0);
    // The cutoff of CGAL's own self-intersection test: below 2000 boxes a
    // plain scan beats the segment tree's recursion on such tight clusters.
    CGAL::box_intersection_d(
        open.begin(), open.end(), all.begin(), all.end(),
        [&](const Box&, const Box& b) { taking_part[static_cast<std::size_t>(b.info())] = 1; }, std::ptrdiff_t(2000));
    for (std::size_t f = 0; f < taking_part.size(); ++f)
      if (taking_part[f]) faces.push_back(Face(static_cast<Mesh::size_type>(f)));
  }
  Mesh sm;
  std::vector<Mesh::Vertex_index> vertex;
  vertex.reserve(static_cast<std::size_t>(mesh.vertex_count()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) vertex.push_back(sm.add_vertex(Kernel::Point_3(P(i, 0), P(i, 1), P(i, 2))));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    const auto face = sm.add_face(vertex[static_cast<std::size_t>(mesh.faces(f, 0))],
                                  vertex[static_cast<std::size_t>(mesh.faces(f, 1))],
                                  vertex[static_cast<std::size_t>(mesh.faces(f, 2))]);
    if (face == Mesh::null_face()) return std::nullopt;
  }
  std::vector<std::pair<Face, Face>> pairs;
  if (faces.size() < kSplitFaces) {
    CGAL::Polygon_mesh_processing::self_intersections(faces, sm, std::back_inserter(pairs));
    return pairs.size();
  }
  // Both cores: the faces split by a plane x = s into those reaching s or
  // below and those reaching s or above (a face across the plane is in
  // both). A face wholly below and one wholly above have disjoint boxes, so
  // they cannot meet: every pair that can is within one half, and a pair of
  // faces across the plane is found in both (counted once). The halves'
  // checks only read the mesh.
  std::vector<std::pair<double, double>> x(faces.size());  // each face's x extent
  std::vector<double> middle(faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const CGAL::Bbox_3 b = box(static_cast<Eigen::Index>(faces[k].idx()));
    x[k] = {b.xmin(), b.xmax()};
    middle[k] = 0.5 * (b.xmin() + b.xmax());
  }
  const auto median = middle.begin() + static_cast<std::ptrdiff_t>(middle.size() / 2);
  std::nth_element(middle.begin(), median, middle.end());
  const double s = *median;
  std::vector<Face> below, above;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    if (x[k].first <= s) below.push_back(faces[k]);
    if (x[k].second >= s) above.push_back(faces[k]);
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
