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
