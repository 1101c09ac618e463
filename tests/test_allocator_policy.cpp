// The allocator's bound for large blocks (runtime/AllocatorPolicy.h, docs/memory.md): once a solver
// exists, a block from LARGE_BLOCK_BYTES up is mapped on its own even after a larger block was freed
// (glibc's own rule then serves it from the heap, which keeps it when freed).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include <deme/deme.h>

#include "runtime/AllocatorPolicy.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

using namespace deme;

namespace {

// A block the compiler cannot drop: written, and its address handed to an opaque statement (an
// allocation that does not escape may be left out altogether).
char* touchedBlock(size_t bytes) {
    char* p = static_cast<char*>(std::malloc(bytes));
    std::memset(p, 1, bytes);
    asm volatile("" : : "r"(p) : "memory");
    return p;
}

}  // namespace

TEST(AllocatorPolicy, LargeBlocksStayMappedAfterALargerOneIsFreed) {
    DEMSolver solver;  // sets the bound (once per process)
#if defined(__GLIBC__)
    // Where the user set the allocator's variables, theirs hold and the solver leaves them.
    if (allocatorTunedByUser()) {
        EXPECT_FALSE(fixLargeBlockBound());
        return;
    }
    EXPECT_TRUE(fixLargeBlockBound());
    // glibc's own rule: freeing a mapped 24 MiB block raises the bound to 24 MiB, and the next
    // 8 MiB block comes from the heap (not mapped). With the bound fixed at 4 MiB it is mapped.
    std::free(touchedBlock(24ul << 20));
    const size_t mappedBefore = mallinfo2().hblkhd;
    char* block = touchedBlock(2 * LARGE_BLOCK_BYTES);
    const size_t mappedWith = mallinfo2().hblkhd;
    std::free(block);
    EXPECT_GE(mappedWith, mappedBefore + 2 * LARGE_BLOCK_BYTES);
    EXPECT_LE(mallinfo2().hblkhd, mappedBefore);  // and given back when freed
#else
    EXPECT_FALSE(fixLargeBlockBound());
#endif
}
