// The entry point of the hand-run comparison programs: the process's
// allocator set as `scanstation` sets it (keep_freed_memory), so that they
// time what the command does; an error (a missing or malformed input file, a
// failed measurement) is printed with the program's name and exits 1,
// instead of terminating with an uncaught exception.
#pragma once

#include "core/process_memory.h"

#include <cstdio>
#include <exception>

namespace scanstation::bench {

inline int guarded_main(int argc, char** argv, int (*run)(int, char**)) {
  keep_freed_memory();
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", argc > 0 ? argv[0] : "bench", e.what());
    return 1;
  }
}

}  // namespace scanstation::bench
