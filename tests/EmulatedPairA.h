// The compact form of a set's As (state/CompactPairA.h) made by the kernels of
// kernels/PairAKernels.cuh run on the host, in the three launches backend/cuda/DevicePairA.cpp makes:
// from As kept whole (`whole`), or from detection's offsets over `spheres` searched spheres. Include
// after the kernel file (between HostKernelEmulation.h and HostKernelEmulationEnd.h's include).
#pragma once

#include <vector>

#include "state/CompactPairAHost.h"

inline deme::HostCompactPairAs compactPairAsByKernels(const deme::bodyID_t* whole, const deme::PairOffset* offset,
                                                      unsigned int spheres, size_t n) {
    using namespace deme;
    HostCompactPairAs c;
    const size_t blocks = pairABlocks(n);
    std::vector<uint32_t> rows(blocks + 1, 0u);
    runThreads(blocks, [&] { deme_pair_a_wide_blocks(whole, offset, spheres, n, rows.data()); });
    uint32_t sum = 0;
    for (uint32_t& r : rows) {
        const uint32_t flag = r;
        r = sum;
        sum += flag;
    }
    c.base.resize(blocks);
    c.delta.assign(n, 0);
    c.wide.assign((size_t)rows[blocks] * PAIR_A_BLOCK, 0);
    runThreads(blocks, [&] { deme_pair_a_bases(whole, offset, spheres, n, rows.data(), c.base.data()); });
    const PairAWriter out{c.base.data(), c.delta.data(), c.wide.data()};
    runThreads(whole ? n : spheres, [&] { deme_pair_a_put(whole, offset, spheres, n, out); });
    return c;
}
