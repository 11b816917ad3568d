// Laser-line extraction on 1280×960 8-bit frame pairs, one core: pairs per
// second (items_per_second), for each sub-pixel fit, against the floor of any
// extractor — one saturating subtraction of the pair (cv::subtract), which
// every method must at least read — and the per-column search of the same
// pair turned a quarter.
//
//   build/bench/laser_line_bench
//
// The pair is a rendered chalice on the simulated turntable with default
// noise, so the noise estimate, rejections and fits see realistic rows.
#include "bench/benchmark_main.h"
#include "acquisition/laser_line.h"
#include "sim/scene_renderer.h"
#include "sim/surface_of_revolution.h"
#include "sim/turntable_rig.h"

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>

namespace {

using namespace scanstation;

struct Pair {
  cv::Mat on, off;
};

const Pair& frame_pair() {
  static const Pair pair = [] {
    const Eigen::MatrixX2d profile = 40.0 * sim::chalice_profile(300);
    const sim::TurntableLaserRig rig = sim::turntable_laser_rig(80.0, 60.0, 1280, 960);
    const sim::SceneRenderer renderer(sim::turntable_scene(sim::surface_of_revolution(profile, 720), rig, 60.0));
    const sim::RenderedView view = renderer.cast(rig.camera, 0.3);
    return Pair{renderer.expose(view, {0}, 1), renderer.expose(view, {}, 2)};
  }();
  return pair;
}

void SubtractReference(benchmark::State& state) {
  const Pair& pair = frame_pair();
  cv::setNumThreads(1);
  cv::Mat difference;
  for (auto _ : state) {
    cv::subtract(pair.on, pair.off, difference);
    benchmark::DoNotOptimize(difference.data);
  }
  state.SetItemsProcessed(state.iterations());
}

void extract_repeatedly(benchmark::State& state, const Pair& pair, const acquisition::LaserLineOptions& options) {
  std::size_t peaks = 0;
  for (auto _ : state) {
    const acquisition::LaserLine line = acquisition::extract_laser_line(pair.on, pair.off, options);
    peaks = line.peaks.size();
    benchmark::DoNotOptimize(line.peaks.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["peaks"] = static_cast<double>(peaks);
}

void Extract(benchmark::State& state) {
  acquisition::LaserLineOptions options;
  options.fit = static_cast<acquisition::PeakFit>(state.range(0));
  extract_repeatedly(state, frame_pair(), options);
}

// The same pair turned a quarter (a horizontal stripe), searched per column:
// the row search plus the transposition of both frames.
void ExtractColumns(benchmark::State& state) {
  static const Pair turned = [] {
    Pair t;
    cv::transpose(frame_pair().on, t.on);
    cv::transpose(frame_pair().off, t.off);
    return t;
  }();
  cv::setNumThreads(1);
  acquisition::LaserLineOptions options;
  options.stripe = acquisition::StripeDirection::horizontal;
  extract_repeatedly(state, turned, options);
}

BENCHMARK(SubtractReference)->Unit(benchmark::kMicrosecond);
BENCHMARK(Extract)->ArgName("fit")->Arg(static_cast<int>(acquisition::PeakFit::centre_of_mass))
    ->Arg(static_cast<int>(acquisition::PeakFit::gaussian))->Arg(static_cast<int>(acquisition::PeakFit::parabolic))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(ExtractColumns)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) { return scanstation::bench::benchmark_main(argc, argv); }
