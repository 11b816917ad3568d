// The incremental constriction against a from-scratch reconstruction of the
// same points, measured in the same run.
//
//   build/bench/incremental_bench timing [--points N] [--batches B] [--every K] [--stop-after S] [--order scan|random|profiles] [--shape S] [--subdivision L] [--noise S] [--margin M] [--local-share F]
//   build/bench/incremental_bench recall [--batches B] [--margin M] [--local-share F] MESH.off ...
//
// timing: N points (default 100000) sampled on a simulated shape (chalice,
// the default: a surface of revolution; or ellipsoid), fed in B batches
// (default 100, i.e. 1% each) in turntable (angle) or random order. Every
// K-th batch (default 1) a from-scratch reconstruct_surface of the points so
// far is timed; prints the per-batch ratio and the median of the ratios, in
// wall time and in thread CPU time.
// --subdivision L: the ellipsoid's mesh is an icosahedron subdivided L times
// (default 5: 20480 flat triangles). The points are sampled on its flat
// triangles, so a cloud much denser than the mesh holds many coplanar points
// per triangle (about 50 at 1M points with L = 5, under one with L = 8),
// which the Delaunay triangulation meets as flat cells with huge
// circumspheres (docs/design.md, incremental constriction).
// --noise S: each point moved along its facet's normal by N(0, S²), in the
// shape's units (the ellipsoid's radii are 3, 2, 1): noise-free samples of
// flat facets lie a rounding error off their planes, which no scanner's
// points do (docs/design.md, incremental constriction).
// --order profiles: what a turntable laser delivers instead, one profile per
// batch: the shape's section by the half-plane through the z axis at the
// batch's angle (B angles round the turn), N/B points along it, evenly
// spaced; the ellipsoid here is the smooth one (no facets), the chalice its
// profile revolved. --noise S then moves each point by N(0, S²) per axis
// (0 gives exactly symmetric rings: a degenerate input for both).
// --local-share F: IncrementalConstriction's local_share (default 0.25; 1
// repairs locally wherever the fill settles).
// --stop-after S feeds only the first S batches (the median is then over
// early batches, each a larger share of the points so far: pessimistic).
//
// recall: per mesh (vertices as input, its triangles as the known answer),
// the triangle recall of the from-scratch result and of the incremental one
// after the last batch, in scan and in random order, and the wider repairs.
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "core/process_memory.h"
#include "core/triangle_recall.h"
#include "reconstruct/boundary_reconstruction.h"
#include "reconstruct/incremental_constriction.h"
#include "sim/arrival_order.h"
#include "sim/sampling.h"
#include "sim/shapes.h"
#include "sim/surface_of_revolution.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

namespace {

using namespace scanstation;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// CPU time of this thread: on a loaded machine it swings far less than wall
// time (both runs here are single-threaded).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Args {
  Eigen::Index points = 100000;
  int batches = 100, every = 1, margin = 2, stop_after = -1;
  double local_share = 0.25;
  bool scan = true;
  bool profiles = false;  // --order profiles: each batch one laser profile (see the header)
  std::string shape = "chalice";
  int subdivision = 5;
  double noise = 0.0;
  std::vector<std::string> files;
};

std::vector<Eigen::Index> arrival_order(const Eigen::MatrixX3d& P, bool scan) {
  return scan ? sim::turntable_order(P) : sim::shuffled_order(P.rows(), 11);
}

// A turntable laser's points: one profile per batch, the object's section by
// the half-plane through the z axis at the batch's angle, `points / batches`
// points along it, evenly spaced (the chalice: by arc length, its two points
// on the axis left out; the ellipsoid (radii 3, 2, 1): evenly in the polar
// angle). --noise moves each point by N(0, noise²) along each axis.
Eigen::MatrixX3d profile_points(const Args& a) {
  const int per = static_cast<int>(std::max<Eigen::Index>(1, a.points / a.batches));
  const Eigen::MatrixX2d section = sim::resample_polyline(sim::chalice_profile(200), per + 2);
  sim::Random random(2024);
  Eigen::MatrixX3d P(static_cast<Eigen::Index>(a.batches) * per, 3);
  Eigen::Index row = 0;
  for (int b = 0; b < a.batches; ++b) {
    const double theta = 2.0 * std::numbers::pi * b / a.batches;
    for (int k = 0; k < per; ++k, ++row) {
      if (a.shape == "ellipsoid") {
        const double phi = std::numbers::pi * (k + 0.5) / per;
        P.row(row) << 3.0 * std::sin(phi) * std::cos(theta), 2.0 * std::sin(phi) * std::sin(theta), std::cos(phi);
      } else {
        const double r = section(k + 1, 0), z = section(k + 1, 1);
        P.row(row) << r * std::cos(theta), r * std::sin(theta), z;
      }
      if (a.noise > 0) P.row(row) += a.noise * Eigen::RowVector3d(random.normal(), random.normal(), random.normal());
    }
  }
  return P;
}

std::size_t batch_end(std::size_t n, int batches, int b) { return n * static_cast<std::size_t>(b + 1) / static_cast<std::size_t>(batches); }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// A reconstruction's faces in the numbering of P (through the arrival order).
Eigen::MatrixX3i in_input_numbering(const SurfaceReconstruction& r, const std::vector<Eigen::Index>& order) {
  Eigen::MatrixX3i faces = r.mesh.faces;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      faces(f, k) = static_cast<int>(order[static_cast<std::size_t>(r.source[static_cast<std::size_t>(faces(f, k))])]);
  return faces;
}

Eigen::MatrixX3d shape_points(const Args& a) {
  if (a.profiles) return profile_points(a);
  const TriangleMesh mesh = a.shape == "ellipsoid" ? sim::ellipsoid({3.0, 2.0, 1.0}, a.subdivision)
                                                   : sim::surface_of_revolution(sim::chalice_profile(200), 256);
  return sim::sample_surface(mesh, a.points, 2024, a.noise).positions;
}

int timing(const Args& a) {
  const Eigen::MatrixX3d P = shape_points(a);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(P.rows()));
  if (a.profiles) {
    std::iota(order.begin(), order.end(), Eigen::Index{0});  // the profiles are made in arrival order
  } else {
    order = arrival_order(P, a.scan);
  }
  const std::size_t n = order.size();
  std::printf("%s (subdivision %d, noise %g), %zu points, %d batches, %s order, margin %d, local share %g\n", a.shape.c_str(),
              a.subdivision, a.noise, n, a.batches, a.profiles ? "profiles" : a.scan ? "scan" : "random", a.margin, a.local_share);
  std::printf("%6s %9s %10s %10s %8s %9s %7s %9s %6s %5s %s\n", "batch", "points", "inc_s", "scratch_s", "ratio", "cpu_ratio",
              "joined", "touched", "rings", "wide", "all");
  IncrementalConstriction inc(surface_defaults(), a.margin, a.local_share);
  std::vector<double> ratios, cpu_ratios, times;
  const int fed = a.stop_after >= 0 ? std::min(a.stop_after, a.batches) : a.batches;
  for (int b = 0; b < fed; ++b) {
    const std::size_t to = batch_end(n, a.batches, b);
    const Eigen::MatrixX3d batch = sim::ordered_rows(P, order, batch_end(n, a.batches, b - 1), to);
    const double cpu_start = thread_cpu_seconds();
    const BatchStats s = inc.add_batch(batch);
    const double inc_cpu = thread_cpu_seconds() - cpu_start;
    times.push_back(s.seconds);
    double scratch = 0.0, scratch_cpu = 0.0;
    if ((b + 1) % a.every == 0 && s.points_so_far >= 4) {
      const Eigen::MatrixX3d so_far = sim::ordered_rows(P, order, 0, to);
      const auto start = std::chrono::steady_clock::now();
      const double scratch_cpu_start = thread_cpu_seconds();
      const SurfaceReconstruction r = reconstruct_surface(so_far, surface_defaults());
      scratch_cpu = thread_cpu_seconds() - scratch_cpu_start;
      scratch = seconds_since(start);
      if (b > 0) {  // the first batch is a from-scratch constriction itself
        ratios.push_back(s.seconds / scratch);
        cpu_ratios.push_back(inc_cpu / scratch_cpu);
      }
    }
    std::printf("%6d %9zu %10.4f %10.4f %8.4f %9.4f %7zu %9zu %6d %5d %d\n", b, s.points_so_far, s.seconds, scratch,
                scratch > 0 ? s.seconds / scratch : 0.0, scratch_cpu > 0 ? inc_cpu / scratch_cpu : 0.0, s.points_joined, s.tetrahedra_touched,
                s.rings, s.wider_repair, s.all_on_boundary);
  }
  std::printf("median per-batch time %.4f s; median ratio to from scratch %.4f wall, %.4f thread CPU (%zu batches compared); "
              "wider repairs %zu\n",
              median(times), median(ratios), median(cpu_ratios), ratios.size(), inc.wider_repairs());
  return 0;
}

int recall(const Args& a) {
  std::printf("%-14s %7s %9s %9s %9s %6s %6s %s\n", "mesh", "points", "scratch", "scan", "random", "wide", "valid", "(recall)");
  for (const std::string& file : a.files) {
    const TriangleMesh truth = io::read_mesh(file);
    const Eigen::MatrixX3d& P = truth.vertices.positions;
    const double scratch = triangle_recall(truth.faces, reconstruct_surface(P, surface_defaults()).mesh.faces);
    double r[2] = {0, 0};
    std::size_t wide = 0;
    bool valid = true;
    for (const bool scan : {true, false}) {
      const std::vector<Eigen::Index> order = arrival_order(P, scan);
      IncrementalConstriction inc(surface_defaults(), a.margin, a.local_share);
      for (int b = 0; b < a.batches; ++b)
        inc.add_batch(sim::ordered_rows(P, order, batch_end(order.size(), a.batches, b - 1), batch_end(order.size(), a.batches, b)));
      const SurfaceReconstruction s = inc.surface();
      const MeshTopology t = mesh_topology(s.mesh);
      valid = valid && t.closed && t.manifold && t.genus == 0 && t.components == 1 && t.isolated_vertices == 0;
      r[scan ? 0 : 1] = triangle_recall(truth.faces, in_input_numbering(s, order));
      wide += inc.wider_repairs();
    }
    const std::string name = file.substr(file.find_last_of('/') + 1);
    std::printf("%-14s %7lld %9.4f %9.4f %9.4f %6zu %6d\n", name.c_str(), static_cast<long long>(P.rows()), scratch, r[0],
                r[1], wide, valid);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  scanstation::keep_freed_memory();  // as `scanstation` does
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s timing|recall [options] [MESH.off ...]\n", argv[0]);
    return 2;
  }
  const std::string mode = argv[1];
  Args a;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (arg == "--points") a.points = std::stoll(value());
    else if (arg == "--batches") a.batches = std::stoi(value());
    else if (arg == "--every") a.every = std::stoi(value());
    else if (arg == "--order") {
      const std::string order = value();
      a.scan = order != "random";
      a.profiles = order == "profiles";
    }
    else if (arg == "--shape") a.shape = value();
    else if (arg == "--margin") a.margin = std::stoi(value());
    else if (arg == "--local-share") a.local_share = std::stod(value());
    else if (arg == "--subdivision") a.subdivision = std::stoi(value());
    else if (arg == "--noise") a.noise = std::stod(value());
    else if (arg == "--stop-after") a.stop_after = std::stoi(value());
    else a.files.push_back(arg);
  }
  if (mode == "timing") return timing(a);
  if (mode == "recall") return recall(a);
  std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
  return 2;
}
