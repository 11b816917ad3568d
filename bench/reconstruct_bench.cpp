// Constriction against its floor: the time CGAL needs to build the Delaunay
// tetrahedralization of the same points, measured in the same run.
//
//   build/bench/reconstruct_bench [--benchmark_filter=/1000000]
//
// Points: 3D uniform on an ellipsoid with radii (3, 2, 1); 2D on a closed
// star-shaped curve and on the chalice silhouette; seeded. 2D has two
// floors: CGAL's range construction (its sort on one core) and
// CgalDelaunay2Sorted, the points sorted on both cores as the
// reconstruction sorts them, then inserted.
#include "bench/benchmark_main.h"
#include "reconstruct/boundary_reconstruction.h"
#include "reconstruct/delaunay_complex.h"
#include "reconstruct/line_of_sight.h"
#include "reconstruct/spatial_order.h"
#include "sim/outlines.h"
#include "sim/random.h"
#include "sim/sampling.h"
#include "sim/surface_of_revolution.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace {

using namespace scanstation;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

const Eigen::MatrixX3d& ellipsoid_points(Eigen::Index n) {
  static std::map<Eigen::Index, Eigen::MatrixX3d> cache;
  auto [it, inserted] = cache.try_emplace(n);
  if (inserted) {
    sim::Random random(2024);
    it->second.resize(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Vector3d p(random.normal(), random.normal(), random.normal());
      it->second.row(i) = (p.normalized().array() * Eigen::Array3d(3, 2, 1)).matrix().transpose();
    }
  }
  return it->second;
}

// The 2D inputs: 0 a five-pointed star-shaped closed curve sampled at random
// angles with noise of 1e-7 (random input order); 1 the chalice silhouette of
// the thesis (Figure 1.1, 2 by 2, perimeter 10.5) sampled uniformly by arc
// length in scan order with noise of 5e-7, a twentieth of the spacing at 1M
// points (at a fifth, plain constriction locks at 1M and augmentation runs).
const Eigen::MatrixX2d& curve_points(int shape, Eigen::Index n) {
  static std::map<std::pair<int, Eigen::Index>, Eigen::MatrixX2d> cache;
  auto [it, inserted] = cache.try_emplace({shape, n});
  if (inserted && shape == 0) {
    sim::Random random(7);
    it->second.resize(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * random.uniform(), r = 1.0 + 0.3 * std::sin(5 * a) + 1e-7 * random.normal();
      it->second.row(i) << r * std::cos(a), r * std::sin(a);
    }
  } else if (inserted) {
    it->second = sim::sample_outline(sim::chalice_outline(400), n, 7, 5e-7);
  }
  return it->second;
}

void CgalDelaunay3(benchmark::State& state) {
  const Eigen::MatrixX3d& P = ellipsoid_points(state.range(0));
  for (auto _ : state) {
    std::vector<Kernel::Point_3> points;
    points.reserve(static_cast<std::size_t>(P.rows()));
    for (Eigen::Index i = 0; i < P.rows(); ++i) points.emplace_back(P(i, 0), P(i, 1), P(i, 2));
    CGAL::Delaunay_triangulation_3<Kernel> dt(points.begin(), points.end());
    benchmark::DoNotOptimize(dt.number_of_cells());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void Reconstruct3(benchmark::State& state) {
  const Eigen::MatrixX3d& P = ellipsoid_points(state.range(0));
  double delaunay = 0, constriction = 0, flips = 0;
  ReconstructionOptions options = surface_defaults();  // as the command does in 3D
  for (auto _ : state) {
    const SurfaceReconstruction r = reconstruct_surface(P, options);
    delaunay += r.statistics.delaunay_seconds;
    constriction += r.statistics.constriction_seconds;
    flips += r.statistics.flip_seconds;
    if (!r.statistics.all_on_boundary) state.SkipWithError("constriction locked");
  }
  state.counters["delaunay_s"] = benchmark::Counter(delaunay, benchmark::Counter::kAvgIterations);
  state.counters["constriction_s"] = benchmark::Counter(constriction, benchmark::Counter::kAvgIterations);
  state.counters["flips_s"] = benchmark::Counter(flips, benchmark::Counter::kAvgIterations);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// Lines of sight through the whole triangulation, as the live boundary of a
// turntable scan walks them once a step: N points on the hollow chalice
// (incremental_bench's shape), each seen from a camera 30° round from its
// own azimuth, level with the cup, four radii out. The walk alone (both
// cores); the triangulation is built once, outside the timing.
void LinesOfSight(benchmark::State& state) {
  const TriangleMesh mesh = sim::surface_of_revolution(sim::chalice_profile(200), 256);
  const Eigen::MatrixX3d P = sim::sample_surface(mesh, state.range(0), 2024).positions;
  const DelaunayComplex<3> dt = delaunay_complex(P);
  const double reach = 4.0 * P.cwiseAbs().maxCoeff(), height = P.col(2).maxCoeff();
  std::vector<SightLine> lines;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double azimuth = std::atan2(P(i, 1), P(i, 0)) + std::numbers::pi / 6;
    lines.push_back({static_cast<int>(i), Eigen::Vector3d(reach * std::cos(azimuth), reach * std::sin(azimuth), height)});
  }
  std::size_t crossed = 0;
  for (auto _ : state) {
    const std::vector<int> depth = line_of_sight_depths(dt, dt.points, lines);
    crossed = static_cast<std::size_t>(std::count_if(depth.begin(), depth.end(), [](int d) { return d >= 0; }));
  }
  state.counters["cells"] = static_cast<double>(dt.cells.rows());
  state.counters["crossed"] = static_cast<double>(crossed);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// 2D: process CPU time (the reconstruction may use more than one thread;
// CGAL's triangulation uses one) and wall time, same points, same run.
void CgalDelaunay2(benchmark::State& state) {
  const Eigen::MatrixX2d& P = curve_points(static_cast<int>(state.range(0)), state.range(1));
  for (auto _ : state) {
    std::vector<Kernel::Point_2> points;
    for (Eigen::Index i = 0; i < P.rows(); ++i) points.emplace_back(P(i, 0), P(i, 1));
    CGAL::Delaunay_triangulation_2<Kernel> dt(points.begin(), points.end());
    benchmark::DoNotOptimize(dt.number_of_faces());
  }
}

// The same triangulation with the points sorted on both cores first, as
// reconstruct_curve sorts them (brio_hilbert_sort), then inserted one
// by one, each located from the last: the floor when both cores may work.
void CgalDelaunay2Sorted(benchmark::State& state) {
  const Eigen::MatrixX2d& P = curve_points(static_cast<int>(state.range(0)), state.range(1));
  for (auto _ : state) {
    std::vector<std::pair<Kernel::Point_2, int>> points;
    points.reserve(static_cast<std::size_t>(P.rows()));
    for (Eigen::Index i = 0; i < P.rows(); ++i) points.emplace_back(Kernel::Point_2(P(i, 0), P(i, 1)), static_cast<int>(i));
    brio_hilbert_sort(points);
    CGAL::Delaunay_triangulation_2<Kernel> dt;
    CGAL::Delaunay_triangulation_2<Kernel>::Vertex_handle hint;
    for (const auto& [point, row] : points) hint = dt.insert(point, hint == nullptr ? nullptr : hint->face());
    benchmark::DoNotOptimize(dt.number_of_faces());
  }
}

void Reconstruct2(benchmark::State& state) {
  const Eigen::MatrixX2d& P = curve_points(static_cast<int>(state.range(0)), state.range(1));
  double delaunay = 0, constriction = 0;
  for (auto _ : state) {
    const CurveReconstruction r = reconstruct_curve(P);
    delaunay += r.statistics.delaunay_seconds;
    constriction += r.statistics.constriction_seconds;
    if (!r.statistics.all_on_boundary) state.SkipWithError("constriction left points inside");
    benchmark::DoNotOptimize(r.polygon.size());
  }
  state.counters["delaunay_s"] = benchmark::Counter(delaunay, benchmark::Counter::kAvgIterations);
  state.counters["constriction_s"] = benchmark::Counter(constriction, benchmark::Counter::kAvgIterations);
}

BENCHMARK(CgalDelaunay3)->RangeMultiplier(10)->Range(10000, 1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(Reconstruct3)->RangeMultiplier(10)->Range(10000, 1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(LinesOfSight)->Arg(30000)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();
// Arguments: shape (0 star, 1 chalice), points. Each reconstruction runs
// right after CGAL's triangulation of the same points, under the same load.
const bool registered_2d = [] {
  for (const int shape : {0, 1})
    for (const int n : {100000, 1000000}) {
      benchmark::RegisterBenchmark("CgalDelaunay2", CgalDelaunay2)->Args({shape, n})->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark("CgalDelaunay2Sorted", CgalDelaunay2Sorted)->Args({shape, n})->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark("Reconstruct2", Reconstruct2)->Args({shape, n})->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);
    }
  return true;
}();

}  // namespace

int main(int argc, char** argv) { return scanstation::bench::benchmark_main(argc, argv); }
