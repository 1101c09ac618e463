// The GPU's late table (state/HistorySlot.h): the slots of the pairs given one between two
// installations, by pair, in an open-addressed table that the host keeps at least twice the entries
// it can get (runtime/HistoryPoolPolicy.h, lateTableEntriesFor).
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

#include "runtime/HistoryPoolPolicy.h"
#include "state/HistoryPool.h"
#include "state/HistorySlot.h"

using namespace deme;

// Entries a power of two, at least 64 and at least twice the late slots a pool can give.
TEST(LateSlotTable, EntriesAreAPowerOfTwoAtLeastTwiceTheLateSlots) {
    EXPECT_EQ(lateTableEntriesFor(0, 0), 64u);
    EXPECT_EQ(lateTableEntriesFor(100, 100), 64u);
    EXPECT_EQ(lateTableEntriesFor(132, 100), 64u);
    EXPECT_EQ(lateTableEntriesFor(133, 100), 128u);
    EXPECT_EQ(lateTableEntriesFor(5, 10), 64u);  // (a trimmed pool: none ranked, fewer slots than before)
    for (size_t late : {1000u, 4096u, 65537u, 3000000u}) {
        const size_t e = lateTableEntriesFor(late + 7, 7);
        EXPECT_EQ(e & (e - 1), 0u) << late;
        EXPECT_GE(e, 2 * late);
        EXPECT_LT(e, 4 * late);
    }
}

// Pairs spread over 2^33 (the top ones too: sets past 2^32 pairs), slots up to 2^31 - 1, inserted
// at half load: each found with its slot, every other pair absent; inserted again into a larger table
// (the host's rehash, through the entries' decoding), the same; a full table refuses the next pair.
TEST(LateSlotTable, EveryInsertedPairIsFoundWithItsSlotAndNoOther) {
    std::mt19937_64 rng(11);
    const size_t top = (size_t(1) << 33) - 2;  // the largest pair an entry holds
    std::uniform_int_distribution<size_t> pick(0, top);
    std::map<size_t, uint32_t> truth;
    const uint32_t late = 3000;
    std::vector<unsigned long long> table(lateTableEntriesFor(late, 0), 0ull);
    const uint32_t mask = (uint32_t)(table.size() - 1);
    for (uint32_t k = 0; truth.size() < late; k++) {
        const size_t pair = truth.size() < 3 ? top - truth.size() : pick(rng);
        if (truth.count(pair)) continue;
        const uint32_t slot = truth.size() == 3 ? HISTORY_SLOT_LIMIT - 1 : k + 1000;
        truth[pair] = slot;
        ASSERT_TRUE(insertLateSlot(table.data(), mask, pair, slot));
    }
    for (const auto& [pair, slot] : truth) ASSERT_EQ(lateTableSlot(table.data(), mask, pair), slot) << pair;
    for (int t = 0; t < 100000; t++) {
        const size_t pair = pick(rng);
        if (!truth.count(pair)) ASSERT_EQ(lateTableSlot(table.data(), mask, pair), NO_HISTORY_SLOT) << pair;
    }
    std::vector<unsigned long long> larger(4 * table.size(), 0ull);
    for (unsigned long long e : table)
        if (e)
            ASSERT_TRUE(
                insertLateSlot(larger.data(), (uint32_t)(larger.size() - 1), lateEntryPair(e), lateEntrySlot(e)));
    for (const auto& [pair, slot] : truth)
        ASSERT_EQ(lateTableSlot(larger.data(), (uint32_t)(larger.size() - 1), pair), slot) << pair;
    std::vector<unsigned long long> small(64, 0ull);
    for (uint32_t p = 0; p < 64; p++) ASSERT_TRUE(insertLateSlot(small.data(), 63u, p * 977u, p));
    EXPECT_FALSE(insertLateSlot(small.data(), 63u, 5u, 64u));
    EXPECT_EQ(lateTableSlot(small.data(), 63u, 977u * 63u), 63u);
    EXPECT_EQ(lateTableSlot(small.data(), 63u, 5u), NO_HISTORY_SLOT);  // a full table: every entry probed
}

// A pair's slot through slotOf: its rank where ranked, its table entry where its late bit is set,
// else none (a pair in the table without its bit is not looked up).
TEST(LateSlotTable, SlotOfReadsRanksThenLateBits) {
    const size_t n = 200;
    std::vector<uint64_t> ranked((n + 63) / 64, 0ull), late(ranked.size(), 0ull);
    std::vector<uint32_t> rankBase(ranked.size() + 1, 0u);
    std::vector<unsigned long long> table(64, 0ull);
    for (size_t i = 0; i < n; i += 3) ranked[i >> 6] |= 1ull << (i & 63);
    for (size_t w = 0; w < ranked.size(); w++) rankBase[w + 1] = rankBase[w] + popcount64(ranked[w]);
    ASSERT_TRUE(insertLateSlot(table.data(), 63u, 7, 500u));
    setPairBit((unsigned long long*)late.data(), 7);
    ASSERT_TRUE(insertLateSlot(table.data(), 63u, 8, 501u));  // no late bit
    RankedSlotsView v;
    v.ranked = ranked.data();
    v.rankBase = rankBase.data();
    v.late = late.data();
    v.lateTable = table.data();
    v.lateMask = 63u;
    for (size_t i = 0; i < n; i++) {
        if (i % 3 == 0)
            EXPECT_EQ(slotOf(v, i), (uint32_t)(i / 3)) << i;
        else if (i == 7)
            EXPECT_EQ(slotOf(v, i), 500u);
        else
            EXPECT_EQ(slotOf(v, i), NO_HISTORY_SLOT) << i;
    }
}
