// Patch construction of the six-split (thesis §9.8), the three-split (§9.6)
// and the adaptive two-split (§9.7) per macro triangle, from 20k to 1.3M
// triangles, against their floor measured in the same run: Steps 1–3 alone
// (one cubic patch per triangle, `macro_patches`); the six-split also into a
// surface reused across iterations (no fresh memory); and the G¹ verification
// of the six-split surface (every shared patch edge sampled at 9 points),
// and the search for its shared patch edges.
//
//   build/bench/smoothing_bench [--benchmark_filter=SixSplit]
//
// Meshes: icospheres of 5..8 subdivisions with every vertex moved radially by
// up to a quarter of the edge length (seeded), so no edge is symmetric and the
// sign condition holds (the surfaces are G¹: Verification reports the largest
// normal angle). Counters: triangles per second
// (one core), bytes of patch data per macro triangle.
#include "bench/benchmark_main.h"
#include "sim/random.h"
#include "sim/shapes.h"
#include "smoothing/macro_patches.h"
#include "smoothing/mesh_edges.h"
#include "smoothing/patch_adjacency.h"
#include "smoothing/g1_verification.h"
#include "smoothing/six_split.h"
#include "smoothing/tessellation.h"
#include "smoothing/three_split.h"
#include "smoothing/two_split.h"
#include "smoothing/vertex_normals.h"

#include <benchmark/benchmark.h>

#include <map>

namespace {

using namespace scanstation;

struct Input {
  TriangleMesh mesh;
  Eigen::MatrixX3d normals;
  MeshEdges edges;
};

const Input& input(int subdivisions) {
  static std::map<int, Input> cache;
  auto [it, inserted] = cache.try_emplace(subdivisions);
  if (inserted) {
    Input& in = it->second;
    in.mesh = sim::icosphere(subdivisions);
    // About a quarter of the edge length, so the G¹ sign condition holds.
    const double noise = 0.3 / double(1 << subdivisions);
    sim::Random random(7);
    for (Eigen::Index v = 0; v < in.mesh.vertex_count(); ++v)
      in.mesh.vertices.positions.row(v) *= 1.0 + noise * (2.0 * random.uniform() - 1.0);
    in.normals = vertex_normals(in.mesh.vertices.positions, in.mesh.faces);
    in.edges = mesh_edges(in.mesh.faces);
  }
  return it->second;
}

void set_counters(benchmark::State& state, std::size_t triangles, std::size_t bytes) {
  state.counters["triangles"] = double(triangles);
  state.counters["triangles_per_s"] =
      benchmark::Counter(double(triangles), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_triangle"] = double(bytes) / double(triangles);
}

void MacroPatches(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::vector<CubicTriangle> patches = macro_patches(in.mesh.vertices.positions, in.mesh.faces, in.normals);
    bytes = patches.size() * sizeof(CubicTriangle);
    benchmark::DoNotOptimize(patches.data());
  }
  set_counters(state, in.mesh.face_count(), bytes);
}

template <bool least_squares_ratio>
void ThreeSplit(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) {
    const BezierSurface surface =
        three_split(in.mesh.vertices.positions, in.mesh.faces, in.normals, in.edges, {least_squares_ratio});
    bytes = surface.patches.size() * sizeof(CubicTriangle) + surface.macro.size() * sizeof(int);
    benchmark::DoNotOptimize(surface.patches.data());
  }
  set_counters(state, in.mesh.face_count(), bytes);
}

void SixSplit(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) {
    const BezierSurface surface = six_split(in.mesh.vertices.positions, in.mesh.faces, in.normals, in.edges);
    bytes = surface.patches.size() * sizeof(CubicTriangle) + surface.macro.size() * sizeof(int);
    benchmark::DoNotOptimize(surface.patches.data());
  }
  set_counters(state, in.mesh.face_count(), bytes);
}

// The same into one surface kept across iterations: its memory is reused, so
// no page faults (the difference to SixSplit is their cost).
void SixSplitReused(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  BezierSurface surface;
  // Once untimed, so that even a single timed iteration (the largest sizes)
  // reuses memory that is already mapped.
  six_split(in.mesh.vertices.positions, in.mesh.faces, in.normals, in.edges, 1.0 / 3.0, surface);
  for (auto _ : state) {
    six_split(in.mesh.vertices.positions, in.mesh.faces, in.normals, in.edges, 1.0 / 3.0, surface);
    benchmark::DoNotOptimize(surface.patches.data());
  }
  set_counters(state, in.mesh.face_count(),
               surface.patches.size() * sizeof(CubicTriangle) + surface.macro.size() * sizeof(int));
}

// Macro triangles with an angle below 55° (the icosphere's least regular
// ones) are two-split candidates; two_split_fraction says how many were used.
void TwoSplit(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  const auto& V = in.mesh.vertices.positions;
  std::size_t bytes = 0, two_split_triangles = 0;
  for (auto _ : state) {
    const std::vector<TwoSplitPair> pairs = two_split_pairs(V, in.mesh.faces, in.edges, 55.0);
    const BezierSurface surface = two_split(V, in.mesh.faces, in.normals, in.edges, pairs);
    bytes = surface.patches.size() * sizeof(CubicTriangle) + surface.macro.size() * sizeof(int);
    two_split_triangles = 3 * in.mesh.face_count() - surface.patches.size();  // 2 patches instead of 3
    benchmark::DoNotOptimize(surface.patches.data());
  }
  set_counters(state, in.mesh.face_count(), bytes);
  state.counters["two_split_fraction"] = double(two_split_triangles) / double(in.mesh.face_count());
}

void Verification(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  const BezierSurface surface = six_split(in.mesh.vertices.positions, in.mesh.faces, in.normals, in.edges);
  double angle = 0.0;
  for (auto _ : state) angle = verify_g1(surface).max_normal_angle;
  set_counters(state, in.mesh.face_count(), 0);
  state.counters["max_normal_angle"] = angle;
}

void EdgeAdjacency(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(mesh_edges(in.mesh.faces).neighbour.data());
  set_counters(state, in.mesh.face_count(), 2 * 3 * sizeof(int) * in.mesh.face_count());
}

// The shared patch edges of the six-split surface, found from the control
// points (done by the verification and once more for the tessellation):
// EdgeAdjacency above, the same pairing from the vertex numbers of the
// macro mesh (six times fewer triangles), is its floor.
void PatchEdges(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  const BezierSurface surface = six_split(in.mesh.vertices.positions, in.mesh.faces, in.normals, in.edges);
  for (auto _ : state) benchmark::DoNotOptimize(patch_adjacency(surface).pairs.data());
  set_counters(state, in.mesh.face_count(), 0);
  state.counters["patches"] = double(surface.patches.size());
}

void Tessellation(benchmark::State& state) {
  const Input& in = input(int(state.range(0)));
  const BezierSurface surface = six_split(in.mesh.vertices.positions, in.mesh.faces, in.normals, in.edges);
  for (auto _ : state) benchmark::DoNotOptimize(tessellate(surface, 4).faces.data());
  set_counters(state, in.mesh.face_count(), 0);
}

}  // namespace

BENCHMARK(MacroPatches)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(SixSplit)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(SixSplitReused)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(ThreeSplit<false>)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(ThreeSplit<true>)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(TwoSplit)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(Verification)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(EdgeAdjacency)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(PatchEdges)->DenseRange(5, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(Tessellation)->DenseRange(5, 6)->Unit(benchmark::kMillisecond);
int main(int argc, char** argv) { return scanstation::bench::benchmark_main(argc, argv); }
