// How the process's allocator treats freed memory.
#pragma once

namespace scanstation {

/// Keeps the memory of freed blocks in the process for later allocations
/// instead of handing it back to the kernel (glibc: large blocks come from
/// the heap, not from mmap, and the heap's top is never trimmed).
///
/// Why: the reconstruction's stages each allocate their arrays after the
/// previous stage freed its own — above all CGAL's triangulation, freed
/// once it is copied to index arrays. By default glibc returns every block
/// over 128 KiB (and up to 32 MiB, by its dynamic threshold) with munmap,
/// so the next stage's arrays fault in fresh pages, and a 4 KiB page fault
/// costs about 11 µs on the machines measured: about a quarter of a cold
/// `scanstation reconstruct` of bunny00 (37.7k points) was page faults
/// (docs/design.md, reconstruction pipeline, "Freed memory stays with the
/// process").
///
/// Process-wide: call it first thing in main, before any thread starts.
/// The resident memory then stays at its peak until the process ends.
/// Returns false where the allocator offers no such setting (not glibc).
bool keep_freed_memory();

}  // namespace scanstation
