// The kernels that make a contact set's As compact (state/CompactPairA.h), in every module whose
// work writes a set: detection (kernels/Detection.cu) and history mapping's merges and trim
// (kernels/HistoryMapping.cu). The As come kept whole (`whole`) or implied by detection's offsets
// over `spheres` searched spheres (`whole` null); backend/cuda/DevicePairA.cpp launches them.
#pragma once

#include "state/CompactPairA.h"

namespace deme {

// 1. wideFlag[k] for each block k of the n pairs.
extern "C" __global__ void deme_pair_a_wide_blocks(const bodyID_t* whole, const PairOffset* offset,
                                                   unsigned int spheres, unsigned long long n, uint32_t* wideFlag) {
    const size_t k = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= pairABlocks(n)) return;
    wideFlag[k] = whole ? pairABlockWideFlag(WholePairASource{whole}, k, n)
                        : pairABlockWideFlag(OffsetPairASource{offset, spheres}, k, n);
}

// 2. Each block's base from the flags' exclusive sum (pairABlocks(n) + 1 entries).
extern "C" __global__ void deme_pair_a_bases(const bodyID_t* whole, const PairOffset* offset, unsigned int spheres,
                                             unsigned long long n, const uint32_t* rows, uint32_t* base) {
    const size_t k = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= pairABlocks(n)) return;
    base[k] = whole ? pairABlockBaseOf(WholePairASource{whole}, k, rows)
                    : pairABlockBaseOf(OffsetPairASource{offset, spheres}, k, rows);
}

// 3. Every pair's A: one thread a pair from `whole`; one a sphere from the offsets (sphere k is the A
// of its pairs).
extern "C" __global__ void deme_pair_a_put(const bodyID_t* whole, const PairOffset* offset, unsigned int spheres,
                                           unsigned long long n, PairAWriter out) {
    const size_t t = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (whole) {
        if (t < n) out.put(t, whole[t]);
        return;
    }
    if (t >= spheres) return;
    for (PairOffset i = offset[t]; i < offset[t + 1]; i++) out.put(i, (bodyID_t)t);
}

}  // namespace deme
