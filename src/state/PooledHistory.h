// The CPU's contact history kept only for the pairs that have some (docs/memory.md). A contact set
// within the safety margin holds many pairs that do not touch (the early mixer: six per sphere, all
// apart), and a built-in model's history of such a pair is all zeros. So while the CPU steps, a set
// may keep the W floats of only the pairs with a history, in a pool, and a pair without a slot
// reads as zeros.
//
// Which pairs have a slot is a bit per pair (`ranked`, one word per 64 pairs), and a pair's slot is
// its rank among them: rankBase[word] plus the bits set below it in its word. So the slots are in
// pair order (the force pass walks them with a counter), and the set holds 1/8 + 1/16 of a byte a
// pair for them instead of a 4-byte index. A pair that starts to touch during the steps takes a
// slot at the end of the force pass that gave it a history (pending, below): at the pool's end, as
// a late pair (ascending, with its slot), until the late pairs are many and the pool is ranked
// again in pair order. A pair keeps its slot, zeros or not, until the next installation, which keeps
// only the slots with a history left.
//
// This form lives only inside the CPU backend's steps: contacts.wildcards (W floats per pair) is
// the history wherever it is not empty, and every host reader of the contact set gets it there
// (Simulation::stateWithContacts densifies, backend/cpu/HistoryForm.h), so checkpoints, edits,
// contact files and the GPU know only that form.
#pragma once

#include <algorithm>
#include <vector>

#include "state/HistorySlot.h"

namespace deme {

// Pending lists over this many bytes are let go after their pass (kept below: no new pages a step).
constexpr size_t PENDING_HISTORY_KEPT_UP_TO = 32u << 20;
// The late pairs are ranked into the pool once they are more than an eighth of the ranked ones
// (and this many): a late pair costs 8 bytes and a search where it is looked up by pair, ranking
// costs a pass over the pool.
constexpr size_t LATE_PAIRS_RANKED_FROM = 4096;

struct PooledHistory;

// The slots of consecutive pairs from pair b on: next(b), next(b + 1), ... in turn, each pair's slot
// or NO_HISTORY_SLOT, the ranked ones by a counter and the late ones by a cursor into their list (no
// rank or search per pair).
struct PooledSlotCursor {
    inline PooledSlotCursor(const PooledHistory& pool, size_t b);
    inline uint32_t next(size_t i);
    const PooledHistory& p;
    uint32_t ranked = 0, late = 0;
};

struct PooledHistory {
    size_t pairs = 0;                          // the set's size when the pool was made (in use while equal)
    std::vector<uint64_t> ranked;              // bit i: pair i has a ranked slot
    std::vector<uint32_t> rankBase;            // per word: the ranked slots of the words before
    std::vector<uint32_t> latePair, lateSlot;  // pairs given a slot since the ranking, ascending
    std::vector<float> values;                 // W floats per slot: the ranked slots, then the late
    // Pairs of the last force pass that took a history without having a slot, per thread of the
    // pass: their indices and W floats each, given slots once the pass is done (the pool is not
    // grown while threads read it).
    std::vector<std::vector<uint32_t>> pendingPair;
    std::vector<std::vector<float>> pendingValues;

    void release() { *this = PooledHistory(); }

    // The pool of a set of n pairs: `bits` says which have a slot (the rank is then the slot), and
    // `pool` holds their W floats each in pair order.
    void assign(size_t n, std::vector<uint64_t>&& bits, std::vector<float>&& pool) {
        release();
        pairs = n;
        ranked.swap(bits);
        values.swap(pool);
        rankBase.resize(ranked.size());
        uint32_t sum = 0;
        for (size_t w = 0; w < ranked.size(); w++) {
            rankBase[w] = sum;
            sum += popcount64(ranked[w]);
        }
    }

    RankedSlotsView view() const {
        return RankedSlotsView{ranked.data(), rankBase.data(), latePair.data(), lateSlot.data(),
                               (uint32_t)latePair.size()};
    }
    // Pair i's slot, or NO_HISTORY_SLOT.
    uint32_t slotOf(size_t i) const { return deme::slotOf(view(), i); }
    bool isRanked(size_t i) const { return (ranked[i >> 6] >> (i & 63)) & 1ull; }

    // Before a force pass: one pending list per thread, emptied ...
    void preparePending(int threads) {
        if (pendingPair.size() < (size_t)threads) {
            pendingPair.resize(threads);
            pendingValues.resize(threads);
        }
        for (std::vector<uint32_t>& v : pendingPair) v.clear();
        for (std::vector<float>& v : pendingValues) v.clear();
    }
    // ... and after it, their pairs given slots at the pool's end, in thread order (which is pair
    // order: the threads take ascending runs of blocks), merged into the late pairs. (Inline: the
    // force pass of a model compiled at run time calls it.)
    void commitPending(unsigned int W) {
        size_t pendingBytes = 0, count = 0;
        for (size_t t = 0; t < pendingPair.size(); t++) count += pendingPair[t].size();
        if (count > 0) {
            std::vector<uint32_t> pair(latePair.size() + count), slot(latePair.size() + count);
            size_t at = 0, late = 0;
            uint32_t next = (uint32_t)(values.size() / W);
            for (size_t t = 0; t < pendingPair.size(); t++)
                for (uint32_t p : pendingPair[t]) {
                    for (; late < latePair.size() && latePair[late] < p; late++, at++) {
                        pair[at] = latePair[late];
                        slot[at] = lateSlot[late];
                    }
                    pair[at] = p;
                    slot[at++] = next++;
                }
            for (; late < latePair.size(); late++, at++) {
                pair[at] = latePair[late];
                slot[at] = lateSlot[late];
            }
            latePair.swap(pair);
            lateSlot.swap(slot);
        }
        for (size_t t = 0; t < pendingPair.size(); t++) {
            // (appended as a run: the pool grows geometrically as pairs start to touch, step by step)
            values.insert(values.end(), pendingValues[t].begin(), pendingValues[t].end());
            pendingBytes += pendingPair[t].capacity() * sizeof(uint32_t) + pendingValues[t].capacity() * sizeof(float);
        }
        // A burst (a bed settling: many pairs touch at once) does not keep its lists' memory.
        if (pendingBytes > PENDING_HISTORY_KEPT_UP_TO) {
            std::vector<std::vector<uint32_t>>().swap(pendingPair);
            std::vector<std::vector<float>>().swap(pendingValues);
        }
        const size_t rankedSlots = values.size() / W - latePair.size();
        if (latePair.size() > LATE_PAIRS_RANKED_FROM && 8 * latePair.size() > rankedSlots) rankLatePairs(W);
    }

    // The late pairs ranked with the others: the pool in pair order again.
    void rankLatePairs(unsigned int W) {
        std::vector<uint64_t> bits(ranked);
        for (uint32_t p : latePair) bits[p >> 6] |= 1ull << (p & 63);
        std::vector<float> pool(values.size());
        size_t at = 0;
        PooledSlotCursor cursor(*this, 0);
        for (size_t i = 0; i < pairs; i++) {
            const uint32_t s = cursor.next(i);
            if (s == NO_HISTORY_SLOT) continue;
            std::copy(values.begin() + (size_t)s * W, values.begin() + (size_t)(s + 1) * W, pool.begin() + at * W);
            at++;
        }
        std::vector<std::vector<uint32_t>> keepPairs(std::move(pendingPair));
        std::vector<std::vector<float>> keepValues(std::move(pendingValues));
        assign(pairs, std::move(bits), std::move(pool));
        pendingPair = std::move(keepPairs);
        pendingValues = std::move(keepValues);
    }

    // What it holds (capacities), for the memory table's contacts and history.
    size_t bytes() const {
        size_t b = ranked.capacity() * sizeof(uint64_t) + rankBase.capacity() * sizeof(uint32_t) +
                   (latePair.capacity() + lateSlot.capacity()) * sizeof(uint32_t) + values.capacity() * sizeof(float);
        for (const std::vector<uint32_t>& v : pendingPair) b += v.capacity() * sizeof(uint32_t);
        for (const std::vector<float>& v : pendingValues) b += v.capacity() * sizeof(float);
        return b;
    }
};

inline PooledSlotCursor::PooledSlotCursor(const PooledHistory& pool, size_t b) : p(pool) {
    if (b < pool.pairs) ranked = rankAt(pool.ranked.data(), pool.rankBase.data(), b);
    late = lateAtOrAfter(pool.latePair.data(), (uint32_t)pool.latePair.size(), b);
}

inline uint32_t PooledSlotCursor::next(size_t i) {
    if (p.isRanked(i)) return ranked++;
    if (late < p.latePair.size() && p.latePair[late] == i) return p.lateSlot[late++];
    return NO_HISTORY_SLOT;
}

}  // namespace deme
