#include "backend/cpu/CarriedPairs.h"

#include <vector>

#include "backend/cpu/HistoryForm.h"
#include "kinematics/CarriedPairsRule.h"
#include "kinematics/HistoryRules.h"
#include "runtime/MemoryAccounting.h"

namespace deme {

namespace {

// A bit per pair (a byte a pair was 17 MB at the early mixer's detection peak, the whole set held).
using PairMarks = std::vector<uint64_t>;
bool marked(const PairMarks& keep, size_t i) { return (keep[i >> 6] >> (i & 63)) & 1ull; }

// `v` (`per` values a pair of n) keeps the pairs marked in `keep`, in order, in storage of its new
// size.
template <class T>
void keepMarked(std::vector<T>& v, const PairMarks& keep, size_t n, size_t kept, size_t per) {
    if (v.empty()) return;
    std::vector<T> out(kept * per);
    size_t at = 0;
    for (size_t i = 0; i < n; i++) {
        if (!marked(keep, i)) continue;
        for (size_t k = 0; k < per; k++) out[at * per + k] = v[i * per + k];
        at++;
    }
    v.swap(out);
}

// The pool of the pairs marked in `keep`: those of them with a slot, ranked in their new order.
void keepPooledMarked(PooledHistory& p, const PairMarks& keep, size_t n, size_t kept, unsigned int W) {
    std::vector<uint64_t> bits((kept + 63) / 64, 0);
    std::vector<float> values;
    size_t at = 0;
    PooledSlotCursor cursor(p, 0);
    for (size_t i = 0; i < n; i++) {
        const uint32_t k = cursor.next(i);  // (every pair in turn)
        if (!marked(keep, i)) continue;
        if (k != NO_HISTORY_SLOT) {
            bits[at >> 6] |= 1ull << (at & 63);
            values.insert(values.end(), p.values.begin() + (size_t)k * W, p.values.begin() + (size_t)(k + 1) * W);
        }
        at++;
    }
    p.assign(kept, std::move(bits), std::move(values));
}

}  // namespace

bool keepOnlyCarriedPairs(SimState& s) {
    ContactArrays& c = s.contacts;
    const size_t n = c.size();
    const unsigned int W = s.numWildcards;
    if (n == 0 || !mayKeepOnlyPairsHandedOn(!s.wildcards.contactInit.empty())) return false;
    const bool pooled = c.historyPooled(W);
    const bool hasMeshState = c.meshState.size() == n, hasPersistent = c.persistent.size() == n;
    // Each pair's mark, a word (64 pairs) at a time so that no two threads write one; a pooled
    // pair's slot by its rank (state/PooledHistory.h).
    const PairMarks keep = pairBits(n, [&](size_t i) {
        const float* h = nullptr;
        if (!pooled)
            h = W ? &c.wildcards[i * W] : nullptr;
        else if (const uint32_t slot = c.pooled.slotOf(i); slot != NO_HISTORY_SLOT)
            h = &c.pooled.values[(size_t)slot * W];
        const uint8_t ms = hasMeshState ? c.meshState[i] : (uint8_t)0;
        const uint8_t ps = hasPersistent ? c.persistent[i] : (uint8_t)0;
        return pairCarriesHistory(h, h ? W : 0u, ms, ps);
    });
    size_t kept = 0;
    for (uint64_t w : keep) kept += popcount64(w);
    if (!keepingOnlyPairsHandedOnPays(n, kept)) return false;
    // One array at a time, the largest first (B), so that each copy is made beside the set less
    // the arrays already trimmed: a detection's peak is here, with the whole set held (A last,
    // made from the runs where the set keeps it so).
    keepMarked(c.geomB, keep, n, kept, 1);
    keepMarked(c.persistent, keep, n, kept, 1);
    keepMarked(c.meshState, keep, n, kept, 1);
    if (pooled)
        keepPooledMarked(c.pooled, keep, n, kept, W);
    else
        keepMarked(c.wildcards, keep, n, kept, W);
    if (c.aAsRuns) {
        // For the kept pairs only: every pair's (4 B a pair) is never made.
        std::vector<bodyID_t> a(kept);
        size_t at = 0;
        for (size_t o = 0; o + 1 < c.ownerAStart.size(); o++)
            for (uint32_t i = c.ownerAStart[o]; i < c.ownerAStart[o + 1]; i++)
                if (marked(keep, i)) a[at++] = (bodyID_t)o;
        c.geomA.swap(a);
        c.aAsRuns = false;
    } else {
        keepMarked(c.geomA, keep, n, kept, 1);
    }
    return true;
}

}  // namespace deme
