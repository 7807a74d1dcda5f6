// How the process keeps the memory it frees (the executables call it first, not the library,
// which a Python process may host).
#pragma once

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace shard {

/// Keeps freed memory in the process for the next allocation of its size. A topology change
/// (a crack split, a remesh, a conversion; in a decomposed run, every gather and new cut) frees
/// and allocates arrays of the whole model; glibc gives blocks above a sliding threshold back to
/// the system at each free and trims the heap's top, so each new array faults every page in
/// again, and a page fault costs microseconds on a virtual machine. Measured on the notched plate
/// on 2 ranks (tests/data/fracture/notched_plate_coarse.yaml, a gather and a cut on most steps):
/// 9 of the 9.5 ms of each gather were page faults. Arrays above 32 MB (glibc's largest mapping
/// threshold) are still mapped and returned, so a large model's peak memory is unchanged.
inline void keep_freed_memory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace shard
