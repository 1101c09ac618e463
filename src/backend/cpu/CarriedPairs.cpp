#include "backend/cpu/CarriedPairs.h"

#include <cstdlib>
#include <cstring>
#include <vector>

#include "kinematics/HistoryRules.h"
#include "parallel/Parallel.h"
#include "runtime/MemoryAccounting.h"

namespace deme {

namespace {

// `v` (`per` values a pair) keeps the pairs marked in `keep`, in order, in storage of its new size.
template <class T>
void keepMarked(std::vector<T>& v, const std::vector<uint8_t>& keep, size_t kept, size_t per) {
    if (v.empty()) return;
    std::vector<T> out(kept * per);
    size_t at = 0;
    for (size_t i = 0; i < keep.size(); i++) {
        if (!keep[i]) continue;
        for (size_t k = 0; k < per; k++) out[at * per + k] = v[i * per + k];
        at++;
    }
    v.swap(out);
}

// The pool of the pairs marked in `keep`: those of them with a slot, ranked in their new order.
void keepPooledMarked(PooledHistory& p, const std::vector<uint8_t>& keep, size_t kept, unsigned int W) {
    std::vector<uint64_t> bits((kept + 63) / 64, 0);
    std::vector<float> values;
    size_t at = 0;
    PooledSlotCursor cursor(p, 0);
    for (size_t i = 0; i < keep.size(); i++) {
        const uint32_t k = cursor.next(i);  // (every pair in turn)
        if (!keep[i]) continue;
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
    if (n == 0 || !s.wildcards.contactInit.empty()) return false;
    // DEME_KEEP_WHOLE_SET=1 keeps every pair (tests compare the two; the trajectory is the same).
    if (const char* v = std::getenv("DEME_KEEP_WHOLE_SET"); v && std::strcmp(v, "1") == 0) return false;
    const bool pooled = c.historyPooled(W);
    const bool hasMeshState = c.meshState.size() == n, hasPersistent = c.persistent.size() == n;
    std::vector<uint8_t> keep(n);
    const int T = n > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1;
    std::vector<size_t> keptBy(T, 0);
    forEachThreadShare(n, T, [&](int t, size_t b, size_t e) {
        PooledSlotCursor cursor(c.pooled, b);
        size_t k = 0;
        for (size_t i = b; i < e; i++) {
            const float* h = nullptr;
            if (!pooled)
                h = W ? &c.wildcards[i * W] : nullptr;
            else if (const uint32_t slot = cursor.next(i); slot != NO_HISTORY_SLOT)
                h = &c.pooled.values[(size_t)slot * W];
            const uint8_t ms = hasMeshState ? c.meshState[i] : (uint8_t)0;
            const uint8_t ps = hasPersistent ? c.persistent[i] : (uint8_t)0;
            keep[i] = pairCarriesHistory(h, h ? W : 0u, ms, ps) ? 1u : 0u;
            k += keep[i];
        }
        keptBy[t] = k;
    });
    size_t kept = 0;
    for (size_t k : keptBy) kept += k;
    // Where most pairs carry something (a settled bed), the copies would cost a pass for little.
    if (2 * kept > n) return false;
    keepMarked(c.geomA, keep, kept, 1);
    keepMarked(c.geomB, keep, kept, 1);
    keepMarked(c.persistent, keep, kept, 1);
    keepMarked(c.meshState, keep, kept, 1);
    if (pooled)
        keepPooledMarked(c.pooled, keep, kept, W);
    else
        keepMarked(c.wildcards, keep, kept, W);
    return kept < n;
}

}  // namespace deme
