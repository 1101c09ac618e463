// A GPU contact set's As in the compact form (state/CompactPairA.h): a base per 32 pairs, a byte a
// pair, a side table for blocks whose As span more than a byte. Made on the host (an upload) and by
// the kernels (kernels/PairAKernels.cuh, run here on the host one thread at a time) from As kept
// whole and from detection's offsets; every A read back is the one put in.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "state/CompactPairAHost.h"

#include "HostKernelEmulation.h"
#include "backend/cuda/kernels/PairAKernels.cuh"
#include "EmulatedPairA.h"
#include "HostKernelEmulationEnd.h"

using namespace deme;

namespace {

// Per-sphere pair counts: mostly a few (the spheres of a packing), with runs of spheres without a
// pair long enough to make a block wide, and a last sphere near the id limit where `nearLimit`.
std::vector<unsigned int> pairCounts(std::mt19937& rng, unsigned int spheres) {
    std::vector<unsigned int> count(spheres, 0u);
    for (unsigned int k = 0; k < spheres; k++) {
        const unsigned int r = (unsigned int)(rng() % 100);
        if (r < 3)
            k += 200 + (unsigned int)(rng() % 400);  // a gap: spheres with no pair
        else if (k < spheres)
            count[k] = r < 60 ? (unsigned int)(rng() % 8) : (unsigned int)(rng() % 40);
    }
    return count;
}

std::vector<bodyID_t> asFromCounts(const std::vector<unsigned int>& count, bodyID_t first = 0) {
    std::vector<bodyID_t> a;
    for (size_t k = 0; k < count.size(); k++) a.insert(a.end(), count[k], (bodyID_t)(first + k));
    return a;
}

std::vector<bodyID_t> readBack(const PairAList& list, size_t n) {
    std::vector<bodyID_t> a(n);
    expandPairAs(list, n, a.data());
    return a;
}

}  // namespace

// Sets of any length (none, under a block, not a multiple of 32), with and without wide blocks,
// read back A for A; a block is wide exactly where its As span more than 255.
TEST(CompactPairA, EveryAReadsBackAndOnlyBlocksSpanningMoreThanAByteAreWide) {
    std::mt19937 rng(11);
    for (int round = 0; round < 40; round++) {
        const unsigned int spheres = round == 0 ? 0u : 1u + (unsigned int)(rng() % 5000);
        const std::vector<bodyID_t> a = asFromCounts(pairCounts(rng, spheres));
        const HostCompactPairAs c = compactPairAsOnHost(a.data(), a.size());
        ASSERT_EQ(c.base.size(), pairABlocks(a.size()));
        ASSERT_EQ(readBack(c.list(), a.size()), a) << "round " << round;
        size_t wide = 0;
        for (size_t k = 0; k < c.base.size(); k++) {
            const bool spansMore = a[pairABlockLast(k, a.size())] - a[pairABlockFirst(k)] > 255;
            EXPECT_EQ((c.base[k] & WIDE_A_BLOCK) != 0, spansMore) << "block " << k;
            wide += spansMore;
        }
        EXPECT_EQ(c.wide.size(), wide * PAIR_A_BLOCK);
    }
    // A span of exactly 255 fits the byte; 256 does not.
    for (bodyID_t span : {255u, 256u}) {
        std::vector<bodyID_t> a(32, 7u);
        a.back() = 7u + span;
        const HostCompactPairAs c = compactPairAsOnHost(a.data(), a.size());
        EXPECT_EQ((c.base[0] & WIDE_A_BLOCK) != 0, span == 256u);
        EXPECT_EQ(readBack(c.list(), a.size()), a);
    }
    // As up to the largest a base can name, and whole lists read as they are.
    std::vector<bodyID_t> high(100);
    for (size_t i = 0; i < high.size(); i++) high[i] = (bodyID_t)(COMPACT_A_SPHERE_LIMIT - 100 + i);
    EXPECT_EQ(readBack(compactPairAsOnHost(high.data(), high.size()).list(), high.size()), high);
    EXPECT_EQ(readBack(wholePairAs(high.data()), high.size()), high);
}

// The kernels make the host's form array for array, from As kept whole and from detection's
// offsets (sphere k the A of its pairs); the offsets' A of every pair is its sphere.
TEST(CompactPairA, KernelsFromWholeAsAndFromOffsetsMakeTheHostsForm) {
    std::mt19937 rng(12);
    for (int round = 0; round < 25; round++) {
        const unsigned int spheres = 1u + (unsigned int)(rng() % 3000);
        const std::vector<unsigned int> count = pairCounts(rng, spheres);
        const std::vector<bodyID_t> a = asFromCounts(count);
        std::vector<PairOffset> offset(spheres + 1, 0u);
        for (unsigned int k = 0; k < spheres; k++) offset[k + 1] = offset[k] + count[k];
        for (size_t i = 0; i < a.size(); i++) ASSERT_EQ(pairAFromOffsets(offset.data(), spheres, i), a[i]);
        if (a.empty()) continue;
        const HostCompactPairAs host = compactPairAsOnHost(a.data(), a.size());
        const HostCompactPairAs fromWhole = compactPairAsByKernels(a.data(), nullptr, 0u, a.size());
        const HostCompactPairAs fromOffsets = compactPairAsByKernels(nullptr, offset.data(), spheres, a.size());
        for (const HostCompactPairAs* k : {&fromWhole, &fromOffsets}) {
            EXPECT_EQ(k->base, host.base) << "round " << round;
            EXPECT_EQ(k->wide, host.wide);
            EXPECT_EQ(k->delta, host.delta);
            EXPECT_EQ(readBack(k->list(), a.size()), a);
        }
    }
}

// Detection's offsets are 64 bits (a GPU set may pass 2^32 pairs): a pair past 2^32 finds its sphere,
// and a block there its first and last pairs, without wrapping.
TEST(CompactPairA, OffsetsPastTwoToTheThirtyTwoNameTheirSpheres) {
    const std::vector<PairOffset> offset = {0ull, 3000000000ull, 3000000000ull, 5000000001ull, 6000000000ull};
    const unsigned int spheres = 4;
    EXPECT_EQ(pairAFromOffsets(offset.data(), spheres, 0), 0u);
    EXPECT_EQ(pairAFromOffsets(offset.data(), spheres, 2999999999ull), 0u);
    EXPECT_EQ(pairAFromOffsets(offset.data(), spheres, 3000000000ull), 2u);  // sphere 1 has none
    EXPECT_EQ(pairAFromOffsets(offset.data(), spheres, 4294967296ull), 2u);
    EXPECT_EQ(pairAFromOffsets(offset.data(), spheres, 5000000001ull), 3u);
    EXPECT_EQ(pairAFromOffsets(offset.data(), spheres, 5999999999ull), 3u);
    const size_t n = 6000000000ull, k = 5000000000ull / PAIR_A_BLOCK;  // the block holding pair 5e9
    EXPECT_EQ(pairABlockFirst(k), 5000000000ull);
    EXPECT_EQ(pairABlockLast(k, n), 5000000031ull);
    EXPECT_EQ(pairABlockLast(pairABlocks(n) - 1, n), n - 1);
    // The block of pairs 5,000,000,000 to 5,000,000,031 spans spheres 2 and 3: one byte apart.
    EXPECT_EQ(pairABlockWideFlag(OffsetPairASource{offset.data(), spheres}, k, n), 0u);
}
