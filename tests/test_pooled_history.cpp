// The pooled form's slots (state/PooledHistory.h): a ranked pair's slot is its rank, a pair that
// took a history during the steps is a late pair at the pool's end, and many late pairs are ranked
// into the pool in pair order again; every pair reads back the history it was given, through all
// three.
#include <gtest/gtest.h>

#include <vector>

#include "state/PooledHistory.h"

using namespace deme;

namespace {

constexpr unsigned int W = 2;

// The history a pair is given here: two floats that name it.
float historyOf(size_t i, unsigned int w) { return (float)(i * 10 + w + 1); }

void expectHistories(const PooledHistory& p, const std::vector<bool>& has) {
    for (size_t i = 0; i < has.size(); i++) {
        const uint32_t k = p.slotOf(i);
        ASSERT_EQ(k != NO_HISTORY_SLOT, (bool)has[i]) << "pair " << i;
        if (k == NO_HISTORY_SLOT) continue;
        for (unsigned int w = 0; w < W; w++) ASSERT_EQ(p.values[(size_t)k * W + w], historyOf(i, w)) << "pair " << i;
    }
}

// Pairs without a slot given a history after the pool was made, as a force pass with two threads
// hands them over (each thread's in ascending order, thread 0's before thread 1's).
void addPending(PooledHistory& p, const std::vector<size_t>& pairs, std::vector<bool>& has) {
    p.preparePending(2);
    for (size_t i : pairs) {
        ASSERT_FALSE(has[i]) << "pair " << i << " has a slot already";
        const int t = i < p.pairs / 2 ? 0 : 1;
        p.pendingPair[t].push_back((uint32_t)i);
        for (unsigned int w = 0; w < W; w++) p.pendingValues[t].push_back(historyOf(i, w));
        has[i] = true;
    }
    p.commitPending(W);
}

}  // namespace

TEST(PooledHistory, RankedLateAndRankedAgainPairsReadTheirHistory) {
    const size_t n = 100000;
    std::vector<bool> has(n, false);
    std::vector<uint64_t> bits((n + 63) / 64, 0);
    std::vector<float> values;
    for (size_t i = 0; i < n; i += 7) {  // every seventh pair has a history
        bits[i / 64] |= 1ull << (i % 64);
        has[i] = true;
        for (unsigned int w = 0; w < W; w++) values.push_back(historyOf(i, w));
    }
    PooledHistory p;
    p.assign(n, std::move(bits), std::move(values));
    const size_t ranked = p.values.size() / W;
    expectHistories(p, has);

    // A few late pairs, in two passes whose pairs interleave: merged in pair order, at the pool's end.
    addPending(p, {3, 50003, 99999}, has);
    addPending(p, {1, 50000, 60002}, has);
    EXPECT_EQ(p.latePair, (std::vector<uint32_t>{1, 3, 50000, 50003, 60002, 99999}));
    EXPECT_EQ(p.values.size() / W, ranked + 6);
    expectHistories(p, has);

    // Many more than an eighth of the ranked ones: ranked again, in pair order, none late.
    std::vector<size_t> many;
    for (size_t i = 2; i < n; i += 5)
        if (!has[i]) many.push_back(i);
    ASSERT_GT(many.size(), ranked / 8 + LATE_PAIRS_RANKED_FROM);
    addPending(p, many, has);
    EXPECT_TRUE(p.latePair.empty());
    expectHistories(p, has);
    uint32_t expected = 0;  // the slots in pair order
    for (size_t i = 0; i < n; i++)
        if (has[i]) ASSERT_EQ(p.slotOf(i), expected++) << "pair " << i;
}
