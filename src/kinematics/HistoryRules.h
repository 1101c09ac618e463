// Contact history across a re-detection (paper §3.2, ARCHITECTURE.md invariant 6) as per-pair
// functions, written once for the CPU's loops (backend/cpu/HistoryMapping.cpp) and the GPU's kernels
// (backend/cuda/kernels/HistoryMapping.cu):
//   1. persistent pairs of the old set that the fresh detection lacks are merged back into it, in key
//      order (each pair finds its place by counting the other set's pairs before it);
//   2. every pair of the new set found in the old one keeps its wildcards, mesh state and persistent
//      flag; a new pair starts from zero, or from the value set for its two families.
// Contact sets are sorted by the pair key (geometry A, then B), so every lookup is a binary search.
#pragma once

#include "dynamics/ContactInputsGather.h"
#include "state/CompactPairA.h"
#include "state/ContactInitRule.h"
#include "state/HistorySlot.h"
#include "state/SphereLayout.h"

namespace deme {

// A contact set's pair keys: geometries A (whole, or the GPU's compact form: state/CompactPairA.h)
// and B of n pairs, sorted by (A, B).
struct ContactKeys {
    PairAList geomA;
    const bodyID_t* geomB;
    size_t n;  // (past 2^32 on the GPU: a pair's index is 64 bits there)
};

DEME_HD_INLINE uint64_t pairKey(bodyID_t a, bodyID_t b) { return ((uint64_t)a << 32) | (uint64_t)b; }

// The first index of `set` whose key is not below `key`.
DEME_HD_INLINE size_t keyLowerBound(const ContactKeys& set, uint64_t key) {
    size_t lo = 0, hi = set.n;
    while (lo < hi) {
        const size_t mid = lo + ((hi - lo) >> 1);
        if (pairKey(set.geomA[mid], set.geomB[mid]) < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

DEME_HD_INLINE bool keyAt(const ContactKeys& set, size_t at, uint64_t key) {
    return at < set.n && pairKey(set.geomA[at], set.geomB[at]) == key;
}

// 1. Whether pair j of the old set is persistent and the fresh set lacks it.
DEME_HD_INLINE bool persistentPairMissing(const ContactKeys& fresh, const ContactKeys& old,
                                          const uint8_t* oldPersistent, size_t j) {
    if (!oldPersistent[j]) return false;
    const uint64_t key = pairKey(old.geomA[j], old.geomB[j]);
    return !keyAt(fresh, keyLowerBound(fresh, key), key);
}

// Where fresh pair i and missing old pair j go in the merged set: their index in their own set plus
// the other set's pairs before them (the two share no key). missingBefore is the exclusive sum of
// persistentPairMissing over the old set.
DEME_HD_INLINE size_t mergedSlotOfFresh(const ContactKeys& fresh, const ContactKeys& old, const uint64_t* missingBefore,
                                        size_t i) {
    return i + missingBefore[keyLowerBound(old, pairKey(fresh.geomA[i], fresh.geomB[i]))];
}
DEME_HD_INLINE size_t mergedSlotOfOld(const ContactKeys& fresh, const ContactKeys& old, const uint64_t* missingBefore,
                                      size_t j) {
    return missingBefore[j] + keyLowerBound(fresh, pairKey(old.geomA[j], old.geomB[j]));
}

// Whether an old pair hands anything to the next set: a history that is not all +0, a mesh state or
// the persistent flag. A pair that hands nothing is, to the next set, the same as one it lacks,
// wherever no contact-init rule gives new pairs values (they would get them, found pairs not).
DEME_HD_INLINE bool pairCarriesHistory(const float* h, unsigned int W, uint8_t meshState, uint8_t persistent) {
    if (meshState || persistent) return true;
    for (unsigned int w = 0; w < W; w++)
        if (!isPositiveZero(h[w])) return true;
    return false;
}

// What the new set takes over from the old one.
struct OldContactHistory {
    ContactKeys keys;
    const float* wildcards;  // W per pair, or W per slot where `slot` is given
    const uint8_t* meshState;   // per pair, or per ranked slot (meshStateBySlot); null: none kept
    const uint8_t* persistent;  // null: none of the old pairs is persistent
    unsigned int W;
    const ContactInitRule* rules;  // initial wildcards of pairs new to the set
    unsigned int numRules;
    // A pooled history (the CPU's, state/PooledHistory.h, or the GPU's, state/HistoryPool.h): each
    // pair's slot in `wildcards`, or NO_HISTORY_SLOT where it has none; none (slots.ranked null)
    // where `wildcards` has W floats per pair.
    RankedSlotsView slots = {};
    // The GPU's pooled form keeps the sphere-triangle pairs' mesh states per ranked slot (every such
    // pair is ranked: state/HistoryPool.h).
    bool meshStateBySlot = false;
};

// Old pair `at`'s mesh state.
DEME_HD_INLINE uint8_t oldMeshState(const OldContactHistory& old, size_t at) {
    if (!old.meshState) return 0;  // (none kept: a scene without triangles)
    if (!old.meshStateBySlot) return old.meshState[at];
    const uint64_t* ranked = old.slots.ranked;
    return pairBit(ranked, at) ? old.meshState[rankAt(ranked, old.slots.rankBase, at)] : (uint8_t)0;
}

// Old pair `at`'s W floats, or null where it has no history (all zeros).
DEME_HD_INLINE const float* oldPairHistory(const OldContactHistory& old, size_t at) {
    if (!old.slots.ranked) return old.wildcards + at * old.W;
    const uint32_t k = slotOf(old.slots, at);
    return k == NO_HISTORY_SLOT ? nullptr : old.wildcards + (size_t)k * old.W;
}

// Whether pair j of a set (read as history mapping reads an old set) hands anything to the next set.
DEME_HD_INLINE bool pairHandsOn(const OldContactHistory& set, size_t j) {
    const float* h = oldPairHistory(set, j);
    return pairCarriesHistory(h, h ? set.W : 0u, oldMeshState(set, j), set.persistent ? set.persistent[j] : (uint8_t)0);
}

// 2a. Where pair i of the new set (keys `fresh`) was in the old set, or old.keys.n where it is new.
DEME_HD_INLINE size_t oldIndexOfPair(const ContactKeys& fresh, const OldContactHistory& old, size_t i) {
    const uint64_t key = pairKey(fresh.geomA[i], fresh.geomB[i]);
    const size_t at = keyLowerBound(old.keys, key);
    return keyAt(old.keys, at, key) ? at : old.keys.n;
}

// 2b. The history of pair i of the new set (keys `fresh`), `at` its index in the
// old set (oldIndexOfPair): its W wildcards, mesh state and persistent flag. `s` gives the
// geometries' owners and families.
template <class S>
DEME_HD_INLINE void pairHistoryFrom(const S& s, const ContactKeys& fresh, const OldContactHistory& old, size_t i,
                                    size_t at, float* wildcards, uint8_t& meshState, uint8_t& persistent) {
    if (at < old.keys.n) {
        const float* h = oldPairHistory(old, at);
        for (unsigned int w = 0; w < old.W; w++) wildcards[w] = h ? h[w] : 0.f;
        meshState = oldMeshState(old, at);
        persistent = old.persistent ? old.persistent[at] : (uint8_t)0;
        return;
    }
    for (unsigned int w = 0; w < old.W; w++) wildcards[w] = 0.f;
    meshState = 0;
    persistent = 0;
    if (old.numRules == 0) return;
    const family_t fa = s.owners.family[sphereOwner(s, fresh.geomA[i])];
    const bodyID_t b = fresh.geomB[i];
    const family_t fb = s.owners.family[geometryOwner(s, contactTypeOf(s, b), b)];
    for (unsigned int r = 0; r < old.numRules; r++) {
        const ContactInitRule& rule = old.rules[r];
        if ((rule.a == fa && rule.b == fb) || (rule.a == fb && rule.b == fa)) wildcards[rule.index] = rule.value;
    }
}

// The GPU's pooled form (state/HistoryPool.h): whether pair i of the new set, its history carried
// over (`h`, W floats), keeps a slot: a history not all +0, or a sphere and a triangle, between
// which the mesh rule hands history during the steps (dynamics/MeshContactRule.h).
template <class S>
DEME_HD_INLINE bool pairKeepsHistorySlot(const S& s, const ContactKeys& fresh, size_t i, const float* h,
                                         unsigned int W) {
    return contactTypeOf(s, fresh.geomB[i]) == SPHERE_TRIANGLE || pairCarriesHistory(h, W, 0, 0);
}

// The W floats `h` into slot k of a pool of W floats per slot.
DEME_HD_INLINE void putInPool(float* pool, uint32_t k, const float* h, unsigned int W) {
    for (unsigned int w = 0; w < W; w++) pool[(size_t)k * W + w] = h[w];
}

// 2. Both: the history of pair i of the new set.
template <class S>
DEME_HD_INLINE void carryPairHistory(const S& s, const ContactKeys& fresh, const OldContactHistory& old, size_t i,
                                     float* wildcards, uint8_t& meshState, uint8_t& persistent) {
    pairHistoryFrom(s, fresh, old, i, oldIndexOfPair(fresh, old, i), wildcards, meshState, persistent);
}

}  // namespace deme
