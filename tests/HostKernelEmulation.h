// Runs a kernel file written for NVRTC on the host, one thread at a time, for tests that check GPU
// kernels without a GPU. Include this, then the kernel file, then HostKernelEmulationEnd.h. Only
// kernels that use nothing of CUDA but the thread index, atomicAdd on 32- and 64-bit unsigned ints and atomicOr on
// 64-bit words can run so;
// blockDim is 1, so a kernel's global index is blockIdx.x.
#pragma once

#include <cstddef>

namespace {
struct EmulatedIndex {
    unsigned int x = 0, y = 0, z = 0;
};
EmulatedIndex blockIdx, threadIdx, blockDim{1, 1, 1};

// One thread at a time: the atomic is a plain add.
inline unsigned int atomicAdd(unsigned int* at, unsigned int v) {
    const unsigned int old = *at;
    *at = old + v;
    return old;
}

inline unsigned long long atomicAdd(unsigned long long* at, unsigned long long v) {
    const unsigned long long old = *at;
    *at = old + v;
    return old;
}

inline unsigned long long atomicOr(unsigned long long* at, unsigned long long v) {
    const unsigned long long old = *at;
    *at = old | v;
    return old;
}

// Runs `kernel` (a call of one kernel) as threads 0 .. n-1.
template <class Kernel>
void runThreads(size_t n, Kernel kernel) {
    for (size_t i = 0; i < n; i++) {
        blockIdx.x = (unsigned int)i;
        kernel();
    }
}

// The same from thread n-1 down to 0: for kernels whose atomics' order must not matter.
template <class Kernel>
void runThreadsReversed(size_t n, Kernel kernel) {
    for (size_t i = n; i-- > 0;) {
        blockIdx.x = (unsigned int)i;
        kernel();
    }
}
}  // namespace

// inline: a kernel header that several kernel files include (kernels/PairAKernels.cuh) may be
// emulated in several tests.
#define __global__ inline
#define __device__
#define __launch_bounds__(...)
