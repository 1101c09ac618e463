// The few CUDA notions that the backend's public headers need, spelled without CUDA's headers, so
// that the rest of the engine (and a build without CUDA) includes them freely and no CUDA type
// (e.g. CUDA's global float3, which clashes with deme::float3 under `using namespace deme`) leaks out.
#pragma once

namespace deme::cuda {

// A cudaStream_t; nullptr is the legacy default stream.
using Stream = void*;

// A launch shape, as CUDA's dim3.
struct Dim3 {
    unsigned int x = 1, y = 1, z = 1;
    Dim3() = default;
    Dim3(unsigned int x_, unsigned int y_ = 1, unsigned int z_ = 1) : x(x_), y(y_), z(z_) {}
};

// Blocks of `threads` needed to cover `n` items, one item per thread.
inline unsigned int blocksFor(unsigned long long n, unsigned int threads) {
    return (unsigned int)((n + threads - 1) / threads);
}

// Threads per block of a step kernel over n items (owners, spheres, contacts): at lab scale (a
// sweep of one wave of a few hundred blocks) 128 spreads it over more multiprocessors than 256;
// large sweeps run faster in blocks of 256. Measured on one H200 (BENCHMARKS.md, SMALL-SYSTEMS):
// 128 against 256 was +1-3 % on the 38,000-sphere drum for the owner kernels and +3-4 % on the drum
// and the impact for the force pass, -1.7 % on the 2.9 M-sphere early mixer for the owner kernels.
inline unsigned int stepThreadsFor(unsigned long long n) { return n < (1ull << 18) ? 128u : 256u; }

// Key bits a radix sort must look at for keys below n (at least 1).
inline int bitsFor(unsigned long long n) {
    int b = 1;
    while (b < 64 && (1ull << b) <= n) b++;
    return b;
}

// What the message of every call says when the library was built without the CUDA backend.
inline const char* cudaNotBuiltMessage() {
    return "the CUDA backend was not built into this library (configure with -DDEME_ENABLE_CUDA=ON on a "
           "machine with the CUDA toolkit)";
}

}  // namespace deme::cuda
