#include "backend/cpu/HistoryForm.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>

#include <deme/Error.h>

#include "parallel/Parallel.h"
#include "runtime/MemoryAccounting.h"

namespace deme {

bool poolsHistory(size_t pairs, size_t withHistory) {
    if (const char* v = std::getenv("DEME_CONTACT_HISTORY")) {
        if (std::strcmp(v, "dense") == 0) return false;
        if (std::strcmp(v, "pooled") == 0) return true;
        if (*v && std::strcmp(v, "auto") != 0)
            throwError("DEME_CONTACT_HISTORY",
                       std::string("is \"") + v + "\"; it may be dense, pooled or auto (the default)");
    }
    return 2 * withHistory <= pairs;
}

void chooseHistoryForm(SimState& s) {
    ContactArrays& c = s.contacts;
    const unsigned int W = s.numWildcards;
    const size_t n = c.size();
    if (c.historyPooled(W)) return;
    // A pool that is not in use (`wildcards` holds the history: a checkpoint read over a copied
    // state) goes.
    c.pooled.release();
    if (W == 0 || n == 0) return;
    // Which pairs keep a slot, a bit each, counted per thread's share of the words, then their
    // histories copied in pair order: the pool's slots.
    std::vector<uint64_t> bits =
        pairBits(n, [&](size_t i) { return pairNeedsHistorySlot(contactTypeAt(s, i), &c.wildcards[i * W], W); });
    const size_t nWords = bits.size();
    const int T = n > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1;
    std::vector<size_t> first(T + 1, 0);
    forEachThreadShare(nWords, T, [&](int t, size_t b, size_t e) {
        size_t k = 0;  // (counted here: neighbouring threads' counts share a cache line)
        for (size_t w = b; w < e; w++) k += popcount64(bits[w]);
        first[t + 1] = k;
    });
    for (int t = 0; t < T; t++) first[t + 1] += first[t];
    if (!poolsHistory(n, first[T])) return;
    std::vector<float> values(first[T] * W);
    forEachThreadShare(nWords, T, [&](int t, size_t b, size_t e) {
        size_t next = first[t];
        for (size_t w = b; w < e; w++)
            for (uint64_t word = bits[w]; word; word &= word - 1) {
                const size_t i = 64 * w + (size_t)__builtin_ctzll(word);
                std::copy(&c.wildcards[i * W], &c.wildcards[i * W] + W, &values[next++ * W]);
            }
    });
    c.pooled.assign(n, std::move(bits), std::move(values));
    releaseVector(c.wildcards);
}

bool densifyHistory(SimState& s) {
    ContactArrays& c = s.contacts;
    const unsigned int W = s.numWildcards;
    if (!c.historyPooled(W)) {
        c.pooled.release();  // (one not in use, as above)
        return false;
    }
    const size_t n = c.size();
    std::vector<float> wildcards(n * W);
    const PooledHistory& p = c.pooled;
    forEachThreadShare(n, n > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1, [&](int, size_t b, size_t e) {
        PooledSlotCursor cursor(p, b);
        for (size_t i = b; i < e; i++)
            if (const uint32_t k = cursor.next(i); k != NO_HISTORY_SLOT)
                std::copy(&p.values[(size_t)k * W], &p.values[(size_t)k * W] + W, &wildcards[i * W]);
    });
    c.wildcards.swap(wildcards);
    c.pooled.release();
    return true;
}

}  // namespace deme
