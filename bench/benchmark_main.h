// The entry point of the Google Benchmark programs: BENCHMARK_MAIN's work,
// after setting the process's allocator as `scanstation` sets it
// (keep_freed_memory), so that they time what the command does.
#pragma once

#include "core/process_memory.h"

#include <benchmark/benchmark.h>

namespace scanstation::bench {

inline int benchmark_main(int argc, char** argv) {
  keep_freed_memory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace scanstation::bench
