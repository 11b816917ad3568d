// Flintstone trees (thesis Ch. 7) against CGAL on the same meshes and queries:
//   - build time and storage of the 3D tree, 10k → 1M triangles (icospheres,
//     plus any meshes given on the command line);
//   - point-inclusion throughput against AABB_tree + Side_of_triangle_mesh
//     (same random query points, answers compared);
//   - mesh–mesh intersection detection against
//     Polygon_mesh_processing::do_intersect (the mesh against a moved copy).
//
//   build/bench/flintstone_bench [--queries N] [--repeat R] [--no-detection] [--max-subdivisions S] [MESH.off ...]
//
// Times are wall-clock seconds, except the query loops: thread CPU seconds,
// the best of R alternating runs of ours and CGAL's. Quote them as ratios.
#include "bench/guarded_main.h"
#include "core/io/mesh_io.h"
#include "reconstruct/flintstone_inclusion.h"
#include "reconstruct/flintstone_intersection.h"
#include "reconstruct/flintstone_tree3.h"
#include "sim/random.h"
#include "sim/shapes.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/intersection.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

namespace {

using namespace scanstation;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// CPU seconds of this thread: on a loaded machine the wall time of a query
/// loop includes the time other processes ran.
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

Mesh to_cgal(const TriangleMesh& m) {
  Mesh mesh;
  for (Eigen::Index v = 0; v < m.vertex_count(); ++v)
    mesh.add_vertex(Kernel::Point_3(m.vertices.positions(v, 0), m.vertices.positions(v, 1), m.vertices.positions(v, 2)));
  for (Eigen::Index f = 0; f < m.face_count(); ++f)
    mesh.add_face(Mesh::Vertex_index(static_cast<Mesh::size_type>(m.faces(f, 0))),
                  Mesh::Vertex_index(static_cast<Mesh::size_type>(m.faces(f, 1))),
                  Mesh::Vertex_index(static_cast<Mesh::size_type>(m.faces(f, 2))));
  return mesh;
}

TriangleMesh moved(TriangleMesh m, const Eigen::Vector3d& offset) {
  m.vertices.positions.rowwise() += offset.transpose();
  return m;
}

struct Options {
  int query_count = 20000;
  int repeat = 1;          ///< timed runs of each query loop (the best is reported)
  bool detection = true;   ///< also time mesh–mesh intersection detection
};

void run(const std::string& name, const TriangleMesh& mesh, const Options& options) {
  const int query_count = options.query_count;
  const Eigen::MatrixX3d& V = mesh.vertices.positions;
  const Eigen::Vector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  sim::Random random(7);
  std::vector<Eigen::Vector3d> queries;
  for (int k = 0; k < query_count; ++k)
    queries.push_back(lo + (hi - lo).cwiseProduct(Eigen::Vector3d(random.uniform(), random.uniform(), random.uniform())));

  auto start = std::chrono::steady_clock::now();
  const FlintstoneTree3 tree = flintstone_tree(mesh);
  const FlintstoneInclusion3 index = inclusion_index(tree);
  const double build = seconds_since(start);
  const Mesh cgal = to_cgal(mesh);
  start = std::chrono::steady_clock::now();
  AabbTree aabb(faces(cgal).first, faces(cgal).second, cgal);
  aabb.accelerate_distance_queries();
  CGAL::Side_of_triangle_mesh<Mesh, Kernel, CGAL::Default, AabbTree> side(aabb);
  const double aabb_build = seconds_since(start);

  // Alternating runs, the best of each kept: a loaded machine slows some
  // runs, rarely all of them.
  std::vector<char> ours(queries.size()), theirs(queries.size());
  double ours_s = INFINITY, theirs_s = INFINITY;
  for (int run = 0; run < options.repeat; ++run) {
    double begin = thread_seconds();
    for (std::size_t k = 0; k < queries.size(); ++k) ours[k] = inside(index, queries[k]);
    ours_s = std::min(ours_s, thread_seconds() - begin);
    begin = thread_seconds();
    for (std::size_t k = 0; k < queries.size(); ++k)
      theirs[k] = side(Kernel::Point_3(queries[k].x(), queries[k].y(), queries[k].z())) != CGAL::ON_UNBOUNDED_SIDE;
    theirs_s = std::min(theirs_s, thread_seconds() - begin);
  }
  std::size_t differ = 0;
  for (std::size_t k = 0; k < queries.size(); ++k) differ += ours[k] != theirs[k];

  // Detection against a copy moved by a tenth of the size (surfaces cross).
  double detect_s = NAN, cgal_detect_s = NAN;
  bool ours_hit = false, theirs_hit = false;
  if (options.detection) {
    const TriangleMesh other = moved(mesh, 0.1 * (hi - lo));
    const FlintstoneTree3 other_tree = flintstone_tree(other);
    const Mesh other_cgal = to_cgal(other);
    start = std::chrono::steady_clock::now();
    ours_hit = solids_intersect(tree, other_tree);
    detect_s = seconds_since(start);
    start = std::chrono::steady_clock::now();
    theirs_hit = CGAL::Polygon_mesh_processing::do_intersect(cgal, other_cgal);
    cgal_detect_s = seconds_since(start);
  }

  std::printf("%-16s %9lld %8.3f %8.3f %6.2f %9.1f %10.0f %10.0f %6.2f %5zu %8.5f %8.5f %6.2f %s\n", name.c_str(),
              static_cast<long long>(mesh.face_count()), build, aabb_build, build / aabb_build,
              static_cast<double>(tree.storage_bytes()) / static_cast<double>(mesh.face_count()),
              query_count / ours_s, query_count / theirs_s, theirs_s / ours_s, differ, detect_s, cgal_detect_s,
              cgal_detect_s / detect_s, !options.detection ? "-" : ours_hit == theirs_hit ? "same" : "DIFFERENT");
  std::fflush(stdout);
}

}  // namespace

static int run(int argc, char** argv) {
  Options options;
  int max_subdivisions = 8;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--queries") && i + 1 < argc) options.query_count = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) options.repeat = std::max(1, std::stoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--no-detection")) options.detection = false;
    else if (!std::strcmp(argv[i], "--max-subdivisions") && i + 1 < argc) max_subdivisions = std::stoi(argv[++i]);
    else files.emplace_back(argv[i]);
  }
  std::printf("%-16s %9s %8s %8s %6s %9s %10s %10s %6s %5s %8s %8s %6s %s\n", "mesh", "faces", "build_s", "aabb_s",
              "ratio", "bytes/f", "ours_q/s", "cgal_q/s", "speed", "diff", "detect_s", "cgal_s", "speed", "answer");
  for (int s = 5; s <= max_subdivisions; ++s) run("icosphere(" + std::to_string(s) + ")", sim::icosphere(s), options);
  for (const std::string& file : files)
    run(std::filesystem::path(file).filename().string(), io::read_mesh(file), options);
  return 0;
}

int main(int argc, char** argv) { return scanstation::bench::guarded_main(argc, argv, run); }
