// The launch lists a GPU step is recorded into (backend/cuda/LaunchList.h): a step graph is made
// again exactly when the list differs from the one it was made from, so equality must see every
// kernel, shape and argument byte, and nothing else. Host-only: nothing here touches a GPU.
#include <gtest/gtest.h>

#include "backend/cuda/LaunchList.h"

using namespace deme::cuda;

namespace {

struct Args {
    double time;
    unsigned int n;
};

LaunchList stepOf(const CudaKernel& a, const CudaKernel& b, unsigned int n, const int* p, double t) {
    LaunchList l;
    l.kernel(a, blocksFor(n, 256), 256, 0, p, n);
    l.kernel(b, 1, 32, 0, Args{t, n}, p);
    return l;
}

}  // namespace

TEST(LaunchList, EqualExactlyWhenKernelsShapesAndArgumentsAre) {
    int x = 0, y = 0;
    CudaKernel a{&x, "a"}, b{&y, "b"};
    const LaunchList base = stepOf(a, b, 1000, &x, 0.5);
    EXPECT_EQ(base.size(), 2u);
    EXPECT_TRUE(base == stepOf(a, b, 1000, &x, 0.5));
    EXPECT_TRUE(base != stepOf(a, b, 1001, &x, 0.5));   // an argument and the grid
    EXPECT_TRUE(base != stepOf(a, b, 1000, &y, 0.5));   // a pointer
    EXPECT_TRUE(base != stepOf(a, b, 1000, &x, 0.25));  // a double inside a struct
    EXPECT_TRUE(base != stepOf(b, a, 1000, &x, 0.5));   // other kernels
    // A kernel recompiled in place (the same object, a new handle) is another kernel.
    CudaKernel moved = a;
    const LaunchList before = stepOf(moved, b, 1000, &x, 0.5);
    moved.handle = &y;
    EXPECT_TRUE(before != stepOf(moved, b, 1000, &x, 0.5));
    // The same kernels launched to overlap the drain of the one before make another graph.
    LaunchList overlapped = stepOf(a, b, 1000, &x, 0.5);
    overlapped.overlapLaunches(true);
    EXPECT_TRUE(base != overlapped);
    // clear() keeps the choice: a step recorded again into the same list overlaps as before.
    overlapped.clear();
    EXPECT_TRUE(overlapped.overlapsLaunches());
}

TEST(LaunchList, AGridOfNoBlocksIsLeftOut) {
    int x = 0;
    CudaKernel a{&x, "a"};
    LaunchList l;
    l.kernel(a, blocksFor(0, 256), 256, 0, 0u);
    EXPECT_TRUE(l.empty());
    l.kernel(a, 1, 1, 0, 0u);
    EXPECT_EQ(l.size(), 1u);
    l.clear();
    EXPECT_TRUE(l.empty());
}

// The step kernels' block size (CudaTypes.h): 128 threads for sweeps of lab scale, 256 for large
// ones, the boundary at 2^18 items; the force pass takes it too unless SetForceCalcThreadsPerBlock
// chose one.
TEST(StepThreads, SmallSweepsIn128LargeIn256) {
    EXPECT_EQ(stepThreadsFor(0), 128u);
    EXPECT_EQ(stepThreadsFor(38001), 128u);              // the small drum's owners
    EXPECT_EQ(stepThreadsFor((1ull << 18) - 1), 128u);  // the drum's 195,000 pairs are below too
    EXPECT_EQ(stepThreadsFor(1ull << 18), 256u);
    EXPECT_EQ(stepThreadsFor(2909520), 256u);  // the early mixer's spheres at r = 2.5 mm
}
