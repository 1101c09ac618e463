#include "backend/cpu/HistoryMapping.h"

#include <algorithm>
#include <string>

#include <deme/Error.h>

#include "backend/cpu/ForcePass.h"
#include "backend/cpu/HistoryForm.h"
#include "kinematics/HistoryRules.h"
#include "parallel/Parallel.h"
#include "runtime/IndexLimits.h"
#include "runtime/MemoryAccounting.h"

namespace deme {

namespace {

ContactKeys keysOf(const std::vector<bodyID_t>& geomA, const std::vector<bodyID_t>& geomB) {
    return ContactKeys{wholePairAs(geomA.data()), geomB.data(), geomA.size()};
}

// Adds to `fresh` the persistent pairs of the current set that it lacks, keeping it sorted by key.
void mergePersistentPairs(const ContactArrays& c, DetectedContacts& fresh) {
    const ContactKeys old = keysOf(c.geomA, c.geomB), freshKeys = keysOf(fresh.geomA, fresh.geomB);
    const size_t nOld = old.n, nFresh = freshKeys.n;
    std::vector<uint64_t> missingBefore(nOld + 1, 0);
#pragma omp parallel for schedule(static) if (nOld > PARALLEL_MIN_ITEMS)
    for (size_t j = 0; j < nOld; j++)
        missingBefore[j] = persistentPairMissing(freshKeys, old, c.persistent.data(), j) ? 1u : 0u;
    std::vector<uint8_t> missing(missingBefore.begin(), missingBefore.end() - 1);
    uint64_t sum = 0;
    for (uint64_t& m : missingBefore) {
        const uint64_t v = m;
        m = sum;
        sum += v;
    }
    if (sum == 0) return;
    requireIndexable((uint64_t)nFresh + sum, "contact pairs (found, and kept as persistent)", FEWER_PAIRS_REMEDY,
                     "DoDynamics");
    DetectedContacts merged;
    merged.geomA.resize(nFresh + sum);
    merged.geomB.resize(nFresh + sum);
#pragma omp parallel for schedule(static) if (nFresh > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < nFresh; i++) {
        const size_t at = mergedSlotOfFresh(freshKeys, old, missingBefore.data(), i);
        merged.geomA[at] = fresh.geomA[i];
        merged.geomB[at] = fresh.geomB[i];
    }
    for (size_t j = 0; j < nOld; j++) {
        if (!missing[j]) continue;
        const size_t at = mergedSlotOfOld(freshKeys, old, missingBefore.data(), j);
        merged.geomA[at] = c.geomA[j];
        merged.geomB[at] = c.geomB[j];
    }
    fresh = std::move(merged);
}

}  // namespace

namespace {

// The most pairs a CPU set indexes (its indices are 32-bit, and a flag bit is kept free).
constexpr size_t MAX_INDEXED_PAIRS = 0x80000000u;

// The new set's mesh states that are not 0 (its sphere-triangle pairs carried from the old set),
// each thread's in pair order: the set's byte a pair is made from them once the set is indexed and
// its geomA let go (A as runs), not beside geomA at an installation's peak (the early mixer's 17 MB).
struct NonzeroMeshStates {
    explicit NonzeroMeshStates(int threads) : byThread(threads) {}
    void record(int thread, size_t i, uint8_t v) {
        if (v) byThread[thread].emplace_back((uint32_t)i, v);
    }
    void into(std::vector<uint8_t>& meshState, size_t n) const {
        meshState.assign(n, 0);
        for (const auto& list : byThread)
            for (const auto& [i, v] : list) meshState[i] = v;
    }
    std::vector<std::vector<std::pair<uint32_t, uint8_t>>> byThread;
};

int mappingThreads(size_t nNew) { return nNew > PARALLEL_MIN_ITEMS ? cpuThreadCount() : 1; }

// The new set's history, W floats per pair, where the set in use keeps that form (a settled bed:
// most pairs touch): one pass, no other array. The form is chosen afterwards (chooseHistoryForm).
void mapDenseHistory(const SimState& s, const DetectedContacts& fresh, const OldContactHistory& old,
                     std::vector<float>& wildcards, NonzeroMeshStates& meshStates, std::vector<uint8_t>& persistent) {
    const size_t nNew = fresh.size();
    const unsigned int W = old.W;
    const ContactKeys freshKeys = keysOf(fresh.geomA, fresh.geomB);
    wildcards.resize(nNew * W);
    forEachThreadShare(nNew, mappingThreads(nNew), [&](int t, size_t b, size_t e) {
        for (size_t i = b; i < e; i++) {
            uint8_t ms, unkept;  // (no pair is persistent where the set keeps no flags)
            carryPairHistory(s, freshKeys, old, i, wildcards.data() + i * W, ms,
                             persistent.empty() ? unkept : persistent[i]);
            meshStates.record(t, i, ms);
        }
    });
}

// The same where the set in use is pooled, or there is none: first whether each pair has a history,
// a bit each (counted per thread's share of the words), then the history in the form that count
// picks (poolsHistory): W floats per pair into `wildcards`, or the pairs that have one into `pool`,
// each pair's old index found again where it is needed (kept between the passes it was 4 B a pair
// at the installation's peak; pooled, only the pairs with a history need it). Returns whether it
// pooled.
bool mapHistoryChoosingForm(const SimState& s, const DetectedContacts& fresh, const OldContactHistory& old,
                            std::vector<float>& wildcards, PooledHistory& pool, NonzeroMeshStates& meshStates,
                            std::vector<uint8_t>& persistent) {
    const size_t nNew = fresh.size();
    const unsigned int W = old.W;
    const ContactKeys freshKeys = keysOf(fresh.geomA, fresh.geomB);
    std::vector<uint64_t> bits((nNew + 63) / 64, 0);
    const size_t nWords = bits.size();
    const int T = mappingThreads(nNew);
    std::vector<size_t> first(T + 1, 0);
    auto pairsOf = [nNew](size_t w, size_t& b, size_t& e) {
        b = 64 * w;
        e = std::min(nNew, b + 64);
    };
    forEachThreadShare(nWords, T, [&](int t, size_t wb, size_t we) {
        std::vector<float> h(W);
        size_t k = 0;  // (counted here: neighbouring threads' counts share a cache line)
        for (size_t w = wb; w < we; w++) {
            size_t b, e;
            pairsOf(w, b, e);
            uint64_t word = 0;
            for (size_t i = b; i < e; i++) {
                uint8_t ms, unkept;  // (as in mapDenseHistory)
                carryPairHistory(s, freshKeys, old, i, h.data(), ms, persistent.empty() ? unkept : persistent[i]);
                meshStates.record(t, i, ms);
                if (pairNeedsHistorySlot(contactTypeOf(s, fresh.geomB[i]), h.data(), W)) {
                    word |= 1ull << (i & 63);
                    k++;
                }
            }
            bits[w] = word;
        }
        first[t + 1] = k;
    });
    for (int t = 0; t < T; t++) first[t + 1] += first[t];
    const bool pooled = nNew > 0 && poolsHistory(nNew, first[T]);
    std::vector<float> values(pooled ? first[T] * W : nNew * W);
    forEachThreadShare(nWords, T, [&](int t, size_t wb, size_t we) {
        size_t next = first[t];
        uint8_t ms, ps;  // (the same as the first pass's)
        for (size_t w = wb; w < we; w++) {
            size_t b, e;
            pairsOf(w, b, e);
            for (size_t i = b; i < e; i++) {
                if (!pooled)
                    carryPairHistory(s, freshKeys, old, i, &values[i * W], ms, ps);
                else if ((bits[w] >> (i & 63)) & 1u)
                    carryPairHistory(s, freshKeys, old, i, &values[next++ * W], ms, ps);
            }
        }
    });
    if (!pooled) {
        wildcards.swap(values);
        return false;
    }
    pool.assign(nNew, std::move(bits), std::move(values));
    return true;
}

}  // namespace

void installDetectedContacts(SimState& s, DetectedContacts& fresh, bool modelWritesPersistent) {
    ContactArrays& c = s.contacts;
    const unsigned int W = s.numWildcards;
    // The old set's reduction index and stored forces are rebuilt for the new set below: emptied,
    // and let go where large, before the new set's arrays are made, while the old set's pairs and
    // history are still held (an installation's peak).
    c.resetIndex();
    const bool anyPersistent = std::find(c.persistent.begin(), c.persistent.end(), 1) != c.persistent.end();
    if (anyPersistent) mergePersistentPairs(c, fresh);
    const size_t nNew = fresh.size();
    if (c.size() >= MAX_INDEXED_PAIRS || nNew >= MAX_INDEXED_PAIRS)
        throwError("DoDynamics", "a contact set of " + std::to_string(std::max(c.size(), nNew)) +
                                     " pairs is more than the CPU backend indexes (2^31)");
    const bool oldPooled = c.historyPooled(W);
    const OldContactHistory old{keysOf(c.geomA, c.geomB),
                                oldPooled ? c.pooled.values.data() : c.wildcards.data(),
                                c.meshState.data(),
                                anyPersistent ? c.persistent.data() : nullptr,
                                W,
                                s.wildcards.contactInit.data(),
                                (unsigned int)s.wildcards.contactInit.size(),
                                oldPooled ? c.pooled.view() : RankedSlotsView{}};
    std::vector<float> wildcards;
    PooledHistory pool;
    // The persistent flags where a pair of the old set has one or the model may set one; else none
    // (every pair's is 0: ContactArrays::persistent).
    std::vector<uint8_t> persistent(anyPersistent || modelWritesPersistent ? nNew : 0);
    NonzeroMeshStates meshStates(mappingThreads(nNew));
    // The history's form (backend/cpu/HistoryForm.h): a dense set is mapped dense and pooled after
    // where few of its pairs have a history; otherwise the form is chosen before the history is made.
    const bool mapDense = W == 0 || (!oldPooled && c.size() > 0);
    const bool pooled = !mapDense && mapHistoryChoosingForm(s, fresh, old, wildcards, pool, meshStates, persistent);
    if (mapDense) mapDenseHistory(s, fresh, old, wildcards, meshStates, persistent);
    c.geomA.swap(fresh.geomA);
    c.geomB.swap(fresh.geomB);
    releaseVector(c.meshState);  // the old set's (made anew below)
    c.persistent.swap(persistent);
    if (pooled) {
        releaseVector(c.wildcards);
        std::swap(c.pooled, pool);
    } else {
        c.pooled.release();
        c.wildcards.swap(wildcards);
    }
    // `fresh` now holds the old set's ids, and the locals its history (swapped out above):
    // released, not kept until the next detection (9 B per pair of the set for the whole run,
    // docs/memory.md), nor through the indexing below (18 B per pair more at the peak).
    fresh = DetectedContacts();
    releaseVector(wildcards);
    pool.release();
    releaseVector(persistent);
    if (mapDense) chooseHistoryForm(s);
    indexContactSet(s);
    // A scene without triangles has no sphere-triangle pair: its set keeps no mesh state (1 B a pair;
    // every reader takes it only for such a pair, and the GPU's upload starts an absent one at zero).
    if (s.triangles.size() != 0) meshStates.into(c.meshState, nNew);
}

void keepPersistentFlagsWhereUsed(ContactArrays& c, bool modelWritesPersistent) {
    if (modelWritesPersistent) {
        if (c.persistent.size() != c.size()) c.persistent.assign(c.size(), 0);
        return;
    }
    if (std::find(c.persistent.begin(), c.persistent.end(), 1) == c.persistent.end()) releaseVector(c.persistent);
}

void indexContactSet(SimState& s) {
    ContactArrays& c = s.contacts;
    const size_t nNew = c.size();
    // Whatever was indexed for another set (before a checkpoint was read into this one, forces
    // stored for it) is emptied: an installation has done so already, before its new arrays.
    c.resetIndex();
    for (size_t i = 0; i < nNew; i++) {
        if (contactTypeAt(s, i) != SPHERE_TRIANGLE) continue;
        if (c.meshContacts.empty() || c.geomA[c.meshContacts.back()] != c.geomA[i])
            c.meshContactGroups.push_back((uint32_t)c.meshContacts.size());
        c.meshContacts.push_back((uint32_t)i);
    }
    c.meshContactGroups.push_back((uint32_t)c.meshContacts.size());
    buildOwnerContactIndex(s);
}

}  // namespace deme
