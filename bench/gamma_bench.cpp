// The γ-neighborhood graph with a negative parameter (lens-shaped
// neighbourhoods, simplices outside the Delaunay triangulation) against the
// O(N^{k+1}) brute force written from Definitions 3.1–3.2 (the tests'
// reference), on the same points in the same run.
//
//   build/bench/gamma_bench [--benchmark_filter=3D]
//
// Arguments: shape (0 uniform in the unit square / cube, 1 on a circle /
// sphere of radius 1 with Gaussian noise of 1% of the radius, the surface
// samples a scan gives), points. Parameter γ(0, −0.5).
#include "bench/benchmark_main.h"
#include "reconstruct/gamma_graph.h"

#include "../tests/reconstruct/gamma_brute_force.h"

#include <benchmark/benchmark.h>

#include <random>

namespace {

using namespace scanstation;

constexpr double kC0 = 0.0, kC1 = -0.5;

template <int D>
Eigen::Matrix<double, Eigen::Dynamic, D> points(int shape, int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Matrix<double, Eigen::Dynamic, D> V(n, D);
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix<double, D, 1> p;
    if (shape == 0) {
      for (int j = 0; j < D; ++j) p[j] = u(rng);
    } else {
      for (int j = 0; j < D; ++j) p[j] = g(rng);
      p = p.normalized() * (1.0 + 0.01 * g(rng));
    }
    V.row(i) = p.transpose();
  }
  return V;
}

template <int D>
void Fast(benchmark::State& state) {
  const auto V = points<D>(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Eigen::Index simplices = 0;
  for (auto _ : state) simplices = gamma_graph(V, kC0, kC1).rows();
  state.counters["simplices"] = static_cast<double>(simplices);
}

template <int D>
void Brute(benchmark::State& state) {
  const auto V = points<D>(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  std::size_t simplices = 0;
  for (auto _ : state) simplices = test::brute_gamma<D>(V, kC0, kC1).size();
  state.counters["simplices"] = static_cast<double>(simplices);
}

const bool registered = [] {
  for (const int shape : {0, 1}) {
    for (const int n : {500, 1000, 2000}) {
      benchmark::RegisterBenchmark("2D/Fast", Fast<2>)->Args({shape, n})->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark("2D/Brute", Brute<2>)->Args({shape, n})->Unit(benchmark::kMillisecond);
    }
    for (const int n : {60, 120, 240}) {
      benchmark::RegisterBenchmark("3D/Fast", Fast<3>)->Args({shape, n})->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark("3D/Brute", Brute<3>)->Args({shape, n})->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace

int main(int argc, char** argv) { return scanstation::bench::benchmark_main(argc, argv); }
