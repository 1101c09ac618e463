// How the process's allocator treats a solver's large arrays (docs/memory.md, "The allocator").
#pragma once

namespace deme {

// Large blocks (from LARGE_BLOCK_BYTES up) are mapped from the system on their own and given back
// when freed. glibc raises that bound as large blocks are freed (up to 32 MiB, and the heap it keeps
// unreturned up to twice as much): a run whose arrays are freed and made again at every contact
// detection then holds tens of MiB of freed memory per thread arena (the early mixer at r = 2.5 mm:
// 59 MiB of its 1,079 MiB peak). Fixing the bound keeps small arrays (a lab-scale bed's, made again
// each step) in the heap, as fast as before. Done once per process, on glibc only, and not where the
// user has set the allocator's own variables (MALLOC_MMAP_THRESHOLD_ and the like, GLIBC_TUNABLES):
// those win. Returns whether the bound was set.
bool fixLargeBlockBound();
// Whether the environment sets the allocator's own variables (fixLargeBlockBound then leaves it).
bool allocatorTunedByUser();

constexpr unsigned long LARGE_BLOCK_BYTES = 4ul << 20;

// Gives the heap's free pages back to the system (glibc's malloc_trim): blocks under
// LARGE_BLOCK_BYTES that a large scene makes at every detection (a pool's bits, their ranks, the
// trim's marks: 1-2 MiB each at 2.9 M spheres) are freed in the heap's middle, where they stay
// resident until reused, some MiB per detection. Called after an installation where the set is
// large (CpuDynamics::install); a no-op elsewhere.
void returnFreedHeapPages();

}  // namespace deme
