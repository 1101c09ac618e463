// Contact history across a re-detection on the GPU: the per-pair rules of kinematics/HistoryRules.h,
// one thread per pair (DeviceHistoryMapping runs them on dT's stream when dT installs a set).
//   1. deme_persistent_missing: which persistent pairs of the old set the new detection lacks;
//   2. deme_persistent_merge: the new set with those pairs merged in, still in key order;
//   3. deme_map_history: wildcards, mesh state and persistent flag of every pair of the new set;
//      or, where the new set keeps its history pooled (state/HistoryPool.h), deme_mark_history_slots
//      (which pairs keep a slot, a bit each), deme_count_marks (each 64 pairs' count), an exclusive
//      sum of the counts (each 64 pairs' first rank), then deme_map_history_pooled (the pool, the
//      mesh states per slot and the persistent flags; a marked pair's slot is its rank). Where no
//      contact-init rule gives new pairs values and no old pair is persistent, only the pairs that
//      carry a history (and the sphere-triangle pairs) keep a slot, and they are found from the old
//      set's side: deme_mark_mesh_pairs, deme_mark_carried_pairs (a search per old pair with a
//      history, not one per new pair), the count and the sum, deme_map_marked_history (a search per
//      marked pair).
// Before a synchronous detection, the set in use may keep only the pairs that hand something to
// the next set (CudaDynamics::beforeDetectNow, as the CPU's backend/cpu/CarriedPairs.h):
// deme_mark_pairs_handed_on (a bit a pair), deme_count_marks, an exclusive sum of the counts (each
// word's first rank), deme_keep_pairs_handed_on. A pooled pool's late table is made larger by
// deme_rehash_late_slots.
// Compiled at run time by NVRTC.
#include "kinematics/HistoryRules.h"
#include "state/HistoryPool.h"
#include "state/HistorySlot.h"
#include "state/StateView.h"

#include "backend/cuda/kernels/PairAKernels.cuh"

namespace deme {

namespace {

__device__ inline size_t globalIndex() { return (size_t)blockIdx.x * blockDim.x + threadIdx.x; }

}  // namespace

// *anyPersistent = 1 if the old set has a persistent pair; where `missing` is given (nOld + 1
// entries, the last left 0 for the exclusive sum), missing[j] = 1 for a persistent pair j of the old
// set that the new set lacks. Launched without `missing` first: a set with no persistent pair needs
// no per-pair scratch.
extern "C" __global__ void deme_persistent_missing(ContactKeys fresh, ContactKeys old, const uint8_t* oldPersistent,
                                                   unsigned long long* missing, unsigned int* anyPersistent) {
    const size_t j = globalIndex();
    if (j >= old.n) return;
    if (oldPersistent[j]) *anyPersistent = 1u;
    if (missing) missing[j] = persistentPairMissing(fresh, old, oldPersistent, j) ? 1u : 0u;
}

// One thread per pair of the fresh set, then per pair of the old set: each goes to its place in the
// merged set. missingBefore is the exclusive sum of deme_persistent_missing's flags.
extern "C" __global__ void deme_persistent_merge(ContactKeys fresh, ContactKeys old, const unsigned long long* missing,
                                                 const unsigned long long* missingBefore, bodyID_t* outA,
                                                 bodyID_t* outB) {
    const size_t t = globalIndex();
    if (t < fresh.n) {
        const size_t i = t;
        const size_t at = mergedSlotOfFresh(fresh, old, (const uint64_t*)missingBefore, i);
        outA[at] = fresh.geomA[i];
        outB[at] = fresh.geomB[i];
    } else if (t < fresh.n + old.n) {
        const size_t j = t - fresh.n;
        if (!missing[j]) return;
        const size_t at = mergedSlotOfOld(fresh, old, (const uint64_t*)missingBefore, j);
        outA[at] = old.geomA[j];
        outB[at] = old.geomB[j];
    }
}

// The history of every pair of the new set. `s` is for the geometries' owners and families.
// freshPersistent (here and below) is null where the new set keeps no flags: none of the old pairs
// is persistent and the model sets none (DeviceHistoryMapping::install).
extern "C" __global__ void deme_map_history(StateView s, ContactKeys fresh, OldContactHistory old,
                                            float* freshWildcards, uint8_t* freshMeshState, uint8_t* freshPersistent) {
    const size_t t = globalIndex();
    if (t >= fresh.n) return;
    const size_t i = t;
    uint8_t persistent;
    carryPairHistory(s, fresh, old, i, freshWildcards + i * old.W, freshMeshState[i], persistent);
    if (freshPersistent) freshPersistent[i] = persistent;
}

// Pooled form, 1: bit i of `ranked` (zeroed before) set where pair i of the new set keeps a slot
// (pairKeepsHistorySlot). old.W is at most MAX_POOLED_HISTORY.
extern "C" __global__ void deme_mark_history_slots(StateView s, ContactKeys fresh, OldContactHistory old,
                                                   unsigned long long* ranked) {
    const size_t t = globalIndex();
    if (t >= fresh.n) return;
    const size_t i = t;
    float h[MAX_POOLED_HISTORY];
    uint8_t meshState, persistent;
    carryPairHistory(s, fresh, old, i, h, meshState, persistent);
    if (pairKeepsHistorySlot(s, fresh, i, h, old.W)) setPairBit(ranked, i);
}

// Pooled form, 3 (after deme_count_marks and the sum): each pair marked in `ranked` takes its rank as
// its slot and puts its history and mesh state there; every pair takes its flag.
extern "C" __global__ void deme_map_history_pooled(StateView s, ContactKeys fresh, OldContactHistory old,
                                                   const uint64_t* ranked, const uint32_t* rankBase, float* pool,
                                                   uint8_t* slotMeshState, uint8_t* freshPersistent) {
    const size_t t = globalIndex();
    if (t >= fresh.n) return;
    const size_t i = t;
    float h[MAX_POOLED_HISTORY];
    uint8_t meshState, persistent;
    carryPairHistory(s, fresh, old, i, h, meshState, persistent);
    if (freshPersistent) freshPersistent[i] = persistent;
    if (!pairBit(ranked, i)) return;  // (no mesh state: a sphere-triangle pair is marked)
    const uint32_t k = rankAt(ranked, rankBase, i);
    putInPool(pool, k, h, old.W);
    slotMeshState[k] = meshState;
}

// Pooled form, from the old set's side, 1: the new set's sphere-triangle pairs marked in `ranked`
// (zeroed before).
extern "C" __global__ void deme_mark_mesh_pairs(StateView s, ContactKeys fresh, unsigned long long* ranked) {
    const size_t t = globalIndex();
    if (t >= fresh.n) return;
    if (contactTypeOf(s, fresh.geomB[t]) == SPHERE_TRIANGLE) setPairBit(ranked, t);
}

// 2: the new set's pair of old pair j's key, where j has a history that is not all +0 and the new
// set has the pair, is marked.
extern "C" __global__ void deme_mark_carried_pairs(ContactKeys fresh, OldContactHistory old,
                                                   unsigned long long* ranked) {
    const size_t j = globalIndex();
    if (j >= old.keys.n) return;
    const float* h = oldPairHistory(old, j);
    if (!h || !pairCarriesHistory(h, old.W, 0, 0)) return;
    const uint64_t key = pairKey(old.keys.geomA[j], old.keys.geomB[j]);
    const size_t at = keyLowerBound(fresh, key);
    if (keyAt(fresh, at, key)) setPairBit(ranked, at);
}

// 3 (after deme_count_marks and the sum): a marked pair takes its rank as its slot and its history,
// mesh state and flag from the old set; the others keep no slot, no mesh state (only sphere-triangle
// pairs have one, and they are marked) and no flag (no old pair is persistent on this path).
extern "C" __global__ void deme_map_marked_history(StateView s, ContactKeys fresh, OldContactHistory old,
                                                   const uint64_t* ranked, const uint32_t* rankBase, float* pool,
                                                   uint8_t* slotMeshState, uint8_t* freshPersistent) {
    const size_t t = globalIndex();
    if (t >= fresh.n) return;
    const size_t i = t;
    if (!pairBit(ranked, i)) {
        if (freshPersistent) freshPersistent[i] = 0u;
        return;
    }
    float h[MAX_POOLED_HISTORY];
    uint8_t meshState, persistent;
    carryPairHistory(s, fresh, old, i, h, meshState, persistent);
    if (freshPersistent) freshPersistent[i] = persistent;
    const uint32_t k = rankAt(ranked, rankBase, i);
    putInPool(pool, k, h, old.W);
    slotMeshState[k] = meshState;
}

// Before a synchronous detection the pairs of the set in use (`set`, its keys, history, mesh state
// and flags as history mapping reads them) that hand something to the next set (pairCarriesHistory)
// are marked, a bit each, and kept in order: a kept pair's place is its rank among the marked ones
// (rankAt, state/HistorySlot.h), so the marks take 12 bytes per 64 pairs, not 4 bytes a pair, beside
// the whole set (the detection's peak). 1: bit j % 64 of marks[j / 64] (zeroed before) for a pair j
// that hands something on.
extern "C" __global__ void deme_mark_pairs_handed_on(OldContactHistory set, unsigned long long* marks) {
    const size_t j = globalIndex();
    if (j >= set.keys.n || !pairHandsOn(set, j)) return;
    atomicOr(&marks[j >> 6], 1ull << (j & 63));
}

// 2 (and the pooled mapping's count): each word's marks counted, and 0 past the last word (numWords + 1
// entries), so that their exclusive sum gives each word's first rank and, at the end, the count
// marked.
extern "C" __global__ void deme_count_marks(const unsigned long long* marks, unsigned int numWords, uint32_t* counts) {
    const size_t w = globalIndex();
    if (w > numWords) return;
    counts[w] = w < numWords ? popcount64(marks[w]) : 0u;
}

// 3: `rankBase` holds the counts' exclusive sum; each kept pair's ids, mesh state (per pair in the
// trimmed set) and flag (where the set has flags), and its W floats of history (a dense set,
// `wildcards` given) or its slot in the pool (a pooled set: a late pair of the trimmed set,
// `keptLate` and its table given, the pool unchanged), go to entry rankAt(j) of the trimmed arrays.
extern "C" __global__ void deme_keep_pairs_handed_on(OldContactHistory set, const unsigned long long* marks,
                                                     const uint32_t* rankBase, bodyID_t* keptA, bodyID_t* keptB,
                                                     uint8_t* keptMeshState, uint8_t* keptPersistent,
                                                     float* keptWildcards, unsigned long long* keptLate,
                                                     unsigned long long* keptTable, uint32_t keptMask) {
    const size_t j = globalIndex();
    if (j >= set.keys.n || !((marks[j >> 6] >> (j & 63)) & 1ull)) return;
    const uint32_t k = rankAt((const uint64_t*)marks, rankBase, j);
    keptA[k] = set.keys.geomA[j];
    keptB[k] = set.keys.geomB[j];
    keptMeshState[k] = oldMeshState(set, j);
    if (set.persistent) keptPersistent[k] = set.persistent[j];
    if (set.slots.ranked) {
        const uint32_t slot = slotOf(set.slots, j);
        if (slot != NO_HISTORY_SLOT && insertLateSlot(keptTable, keptMask, k, slot)) setPairBit(keptLate, k);
    } else {
        for (unsigned int w = 0; w < set.W; w++)
            keptWildcards[(size_t)k * set.W + w] = set.wildcards[(size_t)j * set.W + w];
    }
}

// A late table made larger: each entry of the old one (`oldEntries`) put in the new one (zeroed).
extern "C" __global__ void deme_rehash_late_slots(const unsigned long long* old, unsigned int oldEntries,
                                                  unsigned long long* table, uint32_t mask) {
    const size_t e = globalIndex();
    if (e >= oldEntries || old[e] == 0ull) return;
    insertLateSlot(table, mask, lateEntryPair(old[e]), lateEntrySlot(old[e]));
}

}  // namespace deme
