// Sorting, scanning and reducing device arrays with CUB, compiled ahead of time by nvcc (CUB is a
// template library that NVRTC-compiled kernels would otherwise recompile on every run). Only the
// instantiations the engine needs are built: each costs nvcc time in every build.
//
// All pointers are device pointers; the work is queued on `stream` and the results are ready when
// the stream gets there. An object keeps its scratch memory between calls, so give each stream (the
// kinematics and the dynamics thread) an object of its own. Free of CUDA's headers; in a build
// without CUDA every call throws deme::Error.
#pragma once

#include <cstddef>
#include <cstdint>

#include "backend/cuda/CudaTypes.h"
#include "backend/cuda/DeviceBuffer.h"

namespace deme::cuda {

class DevicePrimitives {
  public:
    // Stable radix sort of (key, value) pairs by key, looking only at key bits [beginBit, endBit)
    // (fewer bits sort faster: voxel ids use 63). In and out arrays must not overlap.
    void sortPairs(const uint64_t* keysIn, uint64_t* keysOut, const uint32_t* valuesIn, uint32_t* valuesOut, size_t n,
                   Stream stream, int beginBit = 0, int endBit = 64);
    void sortPairs(const uint32_t* keysIn, uint32_t* keysOut, const uint32_t* valuesIn, uint32_t* valuesOut, size_t n,
                   Stream stream, int beginBit = 0, int endBit = 32);

    // out[i] = in[0] + ... + in[i-1], out[0] = 0 (in place allowed). Wraps around on overflow. Up to
    // 2^32 - 1 items (a deme::Error past it), the 64-bit one any number.
    void exclusiveSum(const uint32_t* in, uint32_t* out, size_t n, Stream stream);
    void exclusiveSum(const uint64_t* in, uint64_t* out, size_t n, Stream stream);
    // The same of bytes, summed in 32 bits (marks 0 or 1 into indices).
    void exclusiveSum(const uint8_t* in, uint32_t* out, size_t n, Stream stream);

    // *out = in[0] + ... + in[n-1], summed in 64 bits (no wrap: what a 32-bit exclusiveSum of the
    // same counts would wrap is seen here).
    void sum(const uint32_t* in, uint64_t* out, size_t n, Stream stream);

    // *out = the largest (smallest) of in[0..n); for n = 0 the lowest (highest) value of the type.
    // A NaN among floats is not reliably reported: check for NaN separately.
    void reduceMax(const float* in, float* out, size_t n, Stream stream);
    void reduceMax(const double* in, double* out, size_t n, Stream stream);
    void reduceMin(const uint32_t* in, uint32_t* out, size_t n, Stream stream);

    // Scratch memory held now.
    size_t scratchBytes() const { return scratch_.capacityBytes(); }
    // Lets the scratch go (the next call allocates what it needs).
    void releaseScratch() { scratch_.release(); }

  private:
    RawDeviceBuffer scratch_;
};

}  // namespace deme::cuda
