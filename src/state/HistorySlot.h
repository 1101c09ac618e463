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

// The pooled forms' slots as plain pointers, for the per-pair rules: pair i's slot is its rank among
// the ranked pairs (bit i of `ranked`) where it is one; else, on the CPU (state/PooledHistory.h), its
// entry in the late pairs (ascending); on the GPU (state/HistoryPool.h), its entry in the late table
// where bit i of `late` says it has one; else NO_HISTORY_SLOT.
struct RankedSlotsView {
    const uint64_t* ranked = nullptr;  // null: no pool
    const uint32_t* rankBase = nullptr;
    const uint32_t* latePair = nullptr;
    const uint32_t* lateSlot = nullptr;
    uint32_t lateCount = 0;
    // The GPU's late pairs (lateTable given): a bit a pair, and an open-addressed table.
    const uint64_t* late = nullptr;
    const unsigned long long* lateTable = nullptr;
    uint32_t lateMask = 0;  // the table's entries - 1 (a power of two - 1)
};

// The GPU's late table: pairs given a slot between two installations, each an entry
// (pair + 1) << 31 | slot (0: empty) at its hash or after it (linear probing), so that a table
// of zeros is empty; a slot takes 31 bits (a pool holds fewer than 2^31, HISTORY_SLOT_LIMIT) and a
// pair 33, so that sets past 2^32 pairs need no other entry. Its host keeps it at least twice the
// entries it can get (the pool's slots past the ranked ones), so that a probe ends soon and an
// insertion always finds room.
DEME_HD_INLINE uint32_t lateTableHome(size_t pair, uint32_t mask) {
    return (uint32_t)(((uint64_t)pair * 0x9E3779B97F4A7C15ull) >> 32) & mask;
}
DEME_HD_INLINE unsigned long long lateTableEntry(size_t pair, uint32_t slot) {
    return ((unsigned long long)(pair + 1) << 31) | slot;
}
DEME_HD_INLINE size_t lateEntryPair(unsigned long long e) { return (size_t)(e >> 31) - 1; }
DEME_HD_INLINE uint32_t lateEntrySlot(unsigned long long e) { return (uint32_t)(e & 0x7FFFFFFFull); }
// Pair i's slot in the table, or NO_HISTORY_SLOT. (Out of line on the GPU, as the insertion: few
// pairs of a pass take either, and inlined they hold registers the pass's every pair needs.)
DEME_HD_NOINLINE uint32_t lateTableSlot(const unsigned long long* table, uint32_t mask, size_t i) {
    const unsigned long long key = (unsigned long long)(i + 1);
    for (uint32_t h = lateTableHome(i, mask), probes = 0; probes <= mask; h = (h + 1) & mask, probes++) {
        const unsigned long long e = table[h];
        if (e == 0ull) return NO_HISTORY_SLOT;
        if ((e >> 31) == key) return lateEntrySlot(e);
    }
    return NO_HISTORY_SLOT;
}
// Puts pair i's slot in the table (threads at once: each claims an empty entry by a compare and
// swap). False where the table is full.
DEME_HD_NOINLINE bool insertLateSlot(unsigned long long* table, uint32_t mask, size_t i, uint32_t slot) {
    const unsigned long long e = lateTableEntry(i, slot);
    for (uint32_t h = lateTableHome(i, mask), probes = 0; probes <= mask; h = (h + 1) & mask, probes++) {
#ifdef __CUDA_ARCH__
        if (atomicCAS(&table[h], 0ull, e) == 0ull) return true;
#else
        unsigned long long expected = 0ull;
        if (__atomic_compare_exchange_n(&table[h], &expected, e, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
            return true;
#endif
    }
    return false;
}
// Sets bit i of a bit array (threads at once).
DEME_HD_INLINE void setPairBit(unsigned long long* bits, size_t i) {
#ifdef __CUDA_ARCH__
    atomicOr(&bits[i >> 6], 1ull << (i & 63));
#else
    __atomic_fetch_or(&bits[i >> 6], 1ull << (i & 63), __ATOMIC_RELAXED);
#endif
}
DEME_HD_INLINE bool pairBit(const uint64_t* bits, size_t i) { return (bits[i >> 6] >> (i & 63)) & 1ull; }

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

// The GPU's form: a ranked pair's rank, else a late pair's entry in the table, else NO_HISTORY_SLOT
// (so that a pair without a history reads two bits and looks nothing up).
DEME_HD_INLINE uint32_t rankedOrLateSlot(const uint64_t* ranked, const uint32_t* rankBase, const uint64_t* late,
                                         const unsigned long long* lateTable, uint32_t lateMask, size_t i) {
    if (pairBit(ranked, i)) return rankAt(ranked, rankBase, i);
    return pairBit(late, i) ? lateTableSlot(lateTable, lateMask, i) : NO_HISTORY_SLOT;
}

DEME_HD_INLINE uint32_t slotOf(const RankedSlotsView& v, size_t i) {
    if (v.lateTable) return rankedOrLateSlot(v.ranked, v.rankBase, v.late, v.lateTable, v.lateMask, i);
    if (pairBit(v.ranked, i)) return rankAt(v.ranked, v.rankBase, i);
    const uint32_t k = lateAtOrAfter(v.latePair, v.lateCount, i);
    return k < v.lateCount && v.latePair[k] == i ? v.lateSlot[k] : NO_HISTORY_SLOT;
}

// Where a pair's mesh state is (read for a sphere-triangle pair only): states[at], at the pair's
// index where the set keeps a state per pair, at its slot where the GPU's pooled form keeps them per
// ranked slot (state/HistoryPool.h); `states` may be null where the set has no sphere-triangle pair.
struct MeshStateAt {
    const uint8_t* states;
    size_t at;
};

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
