// A contact set's A ids in about 9 bits a pair (the GPU's sets; docs/memory.md, "A in a byte a
// pair"). A set is sorted by (A, B), so 32 neighbouring pairs name a few neighbouring spheres as A:
// each block of 32 pairs keeps a 4-byte base, its first pair's A, and each pair a byte, its A minus
// the base. A block whose As span more than 255 (spheres without pairs between them) keeps its 32
// As whole in a side table, one row a block, and its base says so (the top bit) and names the row.
// Readers take A through PairAList, which also reads A kept whole (one id a pair: the CPU's sets,
// and the writers' scratch before they compact it). Plain data, for NVRTC too.
#pragma once

#include <deme/VariableTypes.h>

#include <deme/HostDevice.h>

namespace deme {

constexpr unsigned int PAIR_A_BLOCK = 32;                  // pairs per base
constexpr uint32_t WIDE_A_BLOCK = 0x80000000u;             // a base's mark: the block's As are in the side table
constexpr uint32_t MAX_A_SPAN_IN_A_BYTE = 255u;            // the most a byte adds to its base
constexpr uint64_t COMPACT_A_SPHERE_LIMIT = WIDE_A_BLOCK;  // As at or past it cannot be a base

// Detection's per-sphere offsets into a set: 64 bits, as a GPU set may pass 2^32 pairs.
using PairOffset = unsigned long long;

DEME_HD_INLINE size_t pairABlocks(size_t pairs) { return (pairs + PAIR_A_BLOCK - 1) / PAIR_A_BLOCK; }

// Whether a block whose first pair's A is `first` and last pair's A is `last` (sorted: first <=
// last) needs the side table.
DEME_HD_INLINE bool pairABlockIsWide(bodyID_t first, bodyID_t last) { return last - first > MAX_A_SPAN_IN_A_BYTE; }

// The block's base, from its first A and its row of the side table where it is wide.
DEME_HD_INLINE uint32_t pairABlockBase(bodyID_t first, bool wide, uint32_t row) {
    return wide ? (WIDE_A_BLOCK | row) : (uint32_t)first;
}

// Pair i's entry in the side table, its block's base marking it wide.
DEME_HD_INLINE size_t wideAEntry(uint32_t base, size_t i) {
    return (size_t)(base & ~WIDE_A_BLOCK) * PAIR_A_BLOCK + i % PAIR_A_BLOCK;
}

// What a read of pair i's A loads first: the whole A, or the block's base and the pair's byte.
struct PairALoaded {
    uint32_t word;
    uint8_t delta;
};

// Pair i's A: whole (one id a pair) where `whole` is set, else from the block's base and the pair's
// byte, or from the side table. A kernel that reads it early may load (`load`) before its dependent
// launch's wait and decode (`decode`) after: the wait orders every load, so that the base and the
// byte go out together (in one expression the compiler moved the byte's load past the base's branch,
// and B's after both: round trips one after another, and the early mixer's force pass 17 % slower).
struct PairAList {
    const bodyID_t* whole;
    const uint32_t* base;  // a block's first A, or WIDE_A_BLOCK | its row of `wide`
    const uint8_t* delta;  // a pair's A minus its block's base
    const bodyID_t* wide;  // PAIR_A_BLOCK As a row
    DEME_HD_INLINE PairALoaded load(size_t i) const {
        if (whole) return PairALoaded{whole[i], 0u};
        return PairALoaded{base[i / PAIR_A_BLOCK], delta[i]};
    }
    DEME_HD_INLINE bodyID_t decode(const PairALoaded& l, size_t i) const {
        if (whole) return l.word;
        if (l.word & WIDE_A_BLOCK) return wide[wideAEntry(l.word, i)];
        return (bodyID_t)(l.word + l.delta);
    }
    DEME_HD_INLINE bodyID_t operator[](size_t i) const { return decode(load(i), i); }
};

DEME_HD_INLINE PairAList wholePairAs(const bodyID_t* a) { return PairAList{a, nullptr, nullptr, nullptr}; }

// Writes pair i's A into the compact form, whose bases are made (pairABlockBase).
struct PairAWriter {
    const uint32_t* base;
    uint8_t* delta;
    bodyID_t* wide;
    DEME_HD_INLINE void put(size_t i, bodyID_t a) const {
        const uint32_t b = base[i / PAIR_A_BLOCK];
        if (b & WIDE_A_BLOCK)
            wide[wideAEntry(b, i)] = a;
        else
            delta[i] = (uint8_t)(a - b);
    }
};

// Pair i's A where the set is sorted by A and A is a searched sphere k whose pairs are
// [offset[k], offset[k + 1]) (detection's exclusive sum over n spheres, offset[n] the total): the
// last k whose offset is not past i.
DEME_HD_INLINE bodyID_t pairAFromOffsets(const PairOffset* offset, unsigned int n, size_t i) {
    unsigned int lo = 0, hi = n;  // offset[lo] <= i < offset[hi]
    while (hi - lo > 1) {
        const unsigned int mid = lo + (hi - lo) / 2;
        if (offset[mid] <= i)
            lo = mid;
        else
            hi = mid;
    }
    return (bodyID_t)lo;
}

// Block k of a set of n pairs: its first and last pair.
DEME_HD_INLINE size_t pairABlockFirst(size_t k) { return k * PAIR_A_BLOCK; }
DEME_HD_INLINE size_t pairABlockLast(size_t k, size_t n) {
    const size_t last = k * PAIR_A_BLOCK + PAIR_A_BLOCK - 1;
    return last < n ? last : n - 1;
}

// The As of a set in order, pair i's by a(i), from which the compact form is made: kept whole, or
// implied by detection's offsets.
struct WholePairASource {
    const bodyID_t* a;
    DEME_HD_INLINE bodyID_t operator()(size_t i) const { return a[i]; }
};
struct OffsetPairASource {
    const PairOffset* offset;
    unsigned int spheres;
    DEME_HD_INLINE bodyID_t operator()(size_t i) const { return pairAFromOffsets(offset, spheres, i); }
};

// 1. Whether block k of n pairs is wide (1) or not (0), summed into each wide block's row.
template <class Source>
DEME_HD_INLINE uint32_t pairABlockWideFlag(const Source& a, size_t k, size_t n) {
    return pairABlockIsWide(a(pairABlockFirst(k)), a(pairABlockLast(k, n))) ? 1u : 0u;
}
// 2. Block k's base from the flags' exclusive sum `rows` (a block is wide where its row differs
// from the next block's).
template <class Source>
DEME_HD_INLINE uint32_t pairABlockBaseOf(const Source& a, size_t k, const uint32_t* rows) {
    return pairABlockBase(a(pairABlockFirst(k)), rows[k + 1] != rows[k], rows[k]);
}
// 3. Every pair's byte or side-table entry: PairAWriter::put.

}  // namespace deme
