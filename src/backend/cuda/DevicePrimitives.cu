// CUB instantiations for DevicePrimitives.h. Every new function here adds to the nvcc time of every
// build (a radix sort is the slow one), so add only what the engine calls.
#include "backend/cuda/DevicePrimitives.h"

#include <deme/Error.h>

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <cuda/std/functional>

#include <algorithm>
#include <limits>
#include <string>

#include "backend/cuda/CudaCheck.h"

namespace deme::cuda {

namespace {

// CUB counts items in 32 bits here, one instantiation per operation: the engine's arrays stay below
// 2^32 entries, except a GPU set's per-pair marks, whose 64-bit sums may count more (exclusiveSumImpl).
uint32_t itemCount(const char* call, size_t n) {
    if (n > std::numeric_limits<uint32_t>::max())
        throwError(call, std::to_string(n) + " items is more than the 2^32 - 1 the device primitives handle");
    return (uint32_t)n;
}

// CUB's two-phase protocol: ask for the scratch size (null scratch), grow the kept scratch, run.
template <class Run>
void withScratch(RawDeviceBuffer& scratch, const char* call, Stream stream, Run run) {
    size_t bytes = 0;
    DEME_CUDA_CHECK(call, run(nullptr, bytes));
    scratch.reserve(std::max<size_t>(bytes, 1), 0, stream);  // a null scratch would mean "ask" again
    DEME_CUDA_CHECK(call, run(scratch.data(), bytes));
}

cudaStream_t toCuda(Stream s) { return static_cast<cudaStream_t>(s); }

template <class Key>
void sortPairsImpl(RawDeviceBuffer& scratch, const Key* keysIn, Key* keysOut, const uint32_t* valuesIn,
                   uint32_t* valuesOut, size_t n, Stream stream, int beginBit, int endBit) {
    const char* call = "DevicePrimitives::sortPairs";
    const uint32_t count = itemCount(call, n);
    if (count == 0) return;
    if (beginBit < 0 || endBit > (int)(8 * sizeof(Key)) || beginBit >= endBit)
        throwError(call, "bit range [" + std::to_string(beginBit) + ", " + std::to_string(endBit) +
                             ") does not fit a " + std::to_string(8 * sizeof(Key)) + "-bit key");
    withScratch(scratch, call, stream, [&](void* temp, size_t& bytes) {
        return cub::DeviceRadixSort::SortPairs(temp, bytes, keysIn, keysOut, valuesIn, valuesOut, count, beginBit,
                                               endBit, toCuda(stream));
    });
}

template <class T>
void exclusiveSumImpl(RawDeviceBuffer& scratch, const T* in, T* out, size_t n, Stream stream) {
    const char* call = "DevicePrimitives::exclusiveSum";
    if (n == 0) return;
    auto scan = [&](auto count) {
        withScratch(scratch, call, stream, [&](void* temp, size_t& bytes) {
            return cub::DeviceScan::ExclusiveSum(temp, bytes, in, out, count, toCuda(stream));
        });
    };
    // 64-bit sums may run over more than 2^32 - 1 items (a GPU set's per-pair marks past 4.29e9
    // pairs): CUB's scan then counts in 64 bits, an instantiation of its own; otherwise in 32.
    if constexpr (sizeof(T) == 8)
        if (n > std::numeric_limits<uint32_t>::max()) return scan((unsigned long long)n);
    scan(itemCount(call, n));
}

}  // namespace

void DevicePrimitives::sortPairs(const uint64_t* keysIn, uint64_t* keysOut, const uint32_t* valuesIn,
                                 uint32_t* valuesOut, size_t n, Stream stream, int beginBit, int endBit) {
    sortPairsImpl(scratch_, keysIn, keysOut, valuesIn, valuesOut, n, stream, beginBit, endBit);
}

void DevicePrimitives::sortPairs(const uint32_t* keysIn, uint32_t* keysOut, const uint32_t* valuesIn,
                                 uint32_t* valuesOut, size_t n, Stream stream, int beginBit, int endBit) {
    sortPairsImpl(scratch_, keysIn, keysOut, valuesIn, valuesOut, n, stream, beginBit, endBit);
}

void DevicePrimitives::exclusiveSum(const uint32_t* in, uint32_t* out, size_t n, Stream stream) {
    exclusiveSumImpl(scratch_, in, out, n, stream);
}

void DevicePrimitives::exclusiveSum(const uint64_t* in, uint64_t* out, size_t n, Stream stream) {
    exclusiveSumImpl(scratch_, in, out, n, stream);
}

void DevicePrimitives::exclusiveSum(const uint8_t* in, uint32_t* out, size_t n, Stream stream) {
    const char* call = "DevicePrimitives::exclusiveSum";
    const uint32_t count = itemCount(call, n);
    if (count == 0) return;
    withScratch(scratch_, call, stream, [&](void* temp, size_t& bytes) {
        return cub::DeviceScan::ExclusiveScan(temp, bytes, in, out, ::cuda::std::plus<uint32_t>{}, uint32_t(0), count,
                                              toCuda(stream));
    });
}

void DevicePrimitives::sum(const uint32_t* in, uint64_t* out, size_t n, Stream stream) {
    const char* call = "DevicePrimitives::sum";
    const uint32_t count = itemCount(call, n);
    // The initial value's type is the accumulator's: 64 bits.
    withScratch(scratch_, call, stream, [&](void* temp, size_t& bytes) {
        return cub::DeviceReduce::Reduce(temp, bytes, in, out, count, ::cuda::std::plus<uint64_t>{}, uint64_t(0),
                                         toCuda(stream));
    });
}

void DevicePrimitives::reduceMax(const float* in, float* out, size_t n, Stream stream) {
    const char* call = "DevicePrimitives::reduceMax";
    const uint32_t count = itemCount(call, n);
    withScratch(scratch_, call, stream, [&](void* temp, size_t& bytes) {
        return cub::DeviceReduce::Max(temp, bytes, in, out, count, toCuda(stream));
    });
}

void DevicePrimitives::reduceMax(const double* in, double* out, size_t n, Stream stream) {
    const char* call = "DevicePrimitives::reduceMax";
    const uint32_t count = itemCount(call, n);
    withScratch(scratch_, call, stream, [&](void* temp, size_t& bytes) {
        return cub::DeviceReduce::Max(temp, bytes, in, out, count, toCuda(stream));
    });
}

void DevicePrimitives::reduceMin(const uint32_t* in, uint32_t* out, size_t n, Stream stream) {
    const char* call = "DevicePrimitives::reduceMin";
    const uint32_t count = itemCount(call, n);
    withScratch(scratch_, call, stream, [&](void* temp, size_t& bytes) {
        return cub::DeviceReduce::Min(temp, bytes, in, out, count, toCuda(stream));
    });
}

}  // namespace deme::cuda
