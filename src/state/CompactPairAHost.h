// The compact form of a contact set's As (state/CompactPairA.h) made and read on the host, with the
// same per-block rules as the GPU's kernels (kernels/PairAKernels.cuh): for a set going up to the
// device, or coming back to the host's readers, which keep A whole.
#pragma once

#include <vector>

#include "state/CompactPairA.h"

namespace deme {

struct HostCompactPairAs {
    std::vector<uint32_t> base;
    std::vector<uint8_t> delta;
    std::vector<bodyID_t> wide;
    PairAList list() const { return PairAList{nullptr, base.data(), delta.data(), wide.data()}; }
};

// The compact form of n As sorted ascending (a contact set's, by its key), each below
// COMPACT_A_SPHERE_LIMIT.
inline HostCompactPairAs compactPairAsOnHost(const bodyID_t* a, size_t n) {
    HostCompactPairAs c;
    const size_t blocks = pairABlocks(n);
    const WholePairASource source{a};
    std::vector<uint32_t> rows(blocks + 1, 0u);
    for (size_t k = 0; k < blocks; k++) rows[k + 1] = rows[k] + pairABlockWideFlag(source, k, n);
    c.base.resize(blocks);
    for (size_t k = 0; k < blocks; k++) c.base[k] = pairABlockBaseOf(source, k, rows.data());
    c.delta.resize(n);
    c.wide.resize((size_t)rows[blocks] * PAIR_A_BLOCK);
    const PairAWriter out{c.base.data(), c.delta.data(), c.wide.data()};
    for (size_t i = 0; i < n; i++) out.put(i, a[i]);
    return c;
}

// The n As of `list`, whole.
inline void expandPairAs(const PairAList& list, size_t n, bodyID_t* a) {
    for (size_t i = 0; i < n; i++) a[i] = list[i];
}

}  // namespace deme
