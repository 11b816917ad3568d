#include "core/process_memory.h"

#include <cstdlib>  // defines __GLIBC__ where glibc is the C library

#if defined(__GLIBC__)
#include <malloc.h>

#include <climits>
#endif

namespace scanstation {

bool keep_freed_memory() {
#if defined(__GLIBC__)
  // No mmap'd chunks: a freed large block stays in the heap for the next
  // one (past a failed heap extension glibc still falls back to mmap). And
  // no trimming, so the freed top of the heap stays mapped too.
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
#else
  return false;
#endif
}

}  // namespace scanstation
