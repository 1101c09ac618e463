// The slot of a pair without history in the CPU's pooled form (state/PooledHistory.h), and what a
// history of zeros is, apart so that the per-pair rules the GPU compiles too
// (kinematics/HistoryRules.h, dynamics/ContactStep.h) can name them.
#pragma once

#include <deme/HostDevice.h>
#include <deme/VariableTypes.h>

namespace deme {

constexpr uint32_t NO_HISTORY_SLOT = 0xFFFFFFFFu;

// The number of set bits of a word.
DEME_HD_INLINE unsigned int popcount64(uint64_t x) {
#ifdef __CUDA_ARCH__
    return (unsigned int)__popcll(x);
#else
    return (unsigned int)__builtin_popcountll(x);
#endif
}

// The pooled form's slots (state/PooledHistory.h) as plain pointers, for the per-pair rules: pair
// i's slot is its rank among the ranked pairs (bit i of `ranked`) where it is one, else its entry in
// the late pairs (ascending), else NO_HISTORY_SLOT.
struct RankedSlotsView {
    const uint64_t* ranked = nullptr;  // null: no pool
    const uint32_t* rankBase = nullptr;
    const uint32_t* latePair = nullptr;
    const uint32_t* lateSlot = nullptr;
    uint32_t lateCount = 0;
};

// The slot of the first ranked pair at or after pair i (its own where it is one).
DEME_HD_INLINE uint32_t rankAt(const uint64_t* ranked, const uint32_t* rankBase, size_t i) {
    return rankBase[i >> 6] + popcount64(ranked[i >> 6] & ((1ull << (i & 63)) - 1ull));
}

// The first late pair at or after pair i (an index into latePair; lateCount where none).
DEME_HD_INLINE uint32_t lateAtOrAfter(const uint32_t* latePair, uint32_t lateCount, size_t i) {
    uint32_t lo = 0, hi = lateCount;
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (latePair[mid] < i)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

DEME_HD_INLINE uint32_t slotOf(const RankedSlotsView& v, size_t i) {
    if ((v.ranked[i >> 6] >> (i & 63)) & 1ull) return rankAt(v.ranked, v.rankBase, i);
    const uint32_t k = lateAtOrAfter(v.latePair, v.lateCount, i);
    return k < v.lateCount && v.latePair[k] == i ? v.lateSlot[k] : NO_HISTORY_SLOT;
}

// Whether a float is +0, bit for bit (a -0 is not).
DEME_HD_INLINE bool isPositiveZero(float v) {
#ifdef __CUDA_ARCH__
    const uint32_t bits = __float_as_uint(v);
#else
    uint32_t bits;
    __builtin_memcpy(&bits, &v, sizeof bits);
#endif
    return bits == 0u;
}

}  // namespace deme
