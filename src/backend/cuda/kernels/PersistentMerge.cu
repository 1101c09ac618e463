// Persistent contacts and initial contact wildcards across a re-detection on the GPU: the rules of
// the CPU's installDetectedContacts (kinematics/HistoryMapping.cpp). Contact sets are sorted by the
// pair key (geometry A, then B), so every lookup is a binary search.
//   1. deme_persistent_missing: which persistent pairs of the old set the new detection lacks;
//   2. deme_persistent_merge: the new set with those pairs merged in, still in key order;
//   3. (history mapping, Detection.cu: wildcards and mesh state of pairs found again)
//   4. deme_persistent_flags: pairs found again keep their persistent flag; new pairs start not
//      persistent, their wildcards at the value set for their two families, if any.
// Compiled at run time by NVRTC.
#include "backend/cuda/kernels/PersistentArgs.cuh"
#include "dynamics/ContactInputsGather.h"
#include "state/StateView.h"

namespace deme {

namespace {

__device__ inline size_t globalIndex() { return (size_t)blockIdx.x * blockDim.x + threadIdx.x; }

__device__ inline unsigned long long pairKey(bodyID_t a, bodyID_t b) { return ((unsigned long long)a << 32) | b; }

// The first index of the sorted set (a, b)[0, n) whose key is not below `key`.
__device__ inline unsigned int lowerBound(const bodyID_t* a, const bodyID_t* b, unsigned int n,
                                          unsigned long long key) {
    unsigned int lo = 0, hi = n;
    while (lo < hi) {
        const unsigned int mid = (lo + hi) >> 1;
        if (pairKey(a[mid], b[mid]) < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

}  // namespace

// missing[j] = 1 for a persistent pair j of the old set that the new set lacks (missing has nOld + 1
// entries, the last left 0 for the exclusive sum); *anyPersistent = 1 if the old set has any.
extern "C" __global__ void deme_persistent_missing(ContactKeys fresh, ContactKeys old, const uint8_t* oldPersistent,
                                                   unsigned int* missing, unsigned int* anyPersistent) {
    const size_t j = globalIndex();
    if (j >= old.n) return;
    unsigned int m = 0;
    if (oldPersistent[j]) {
        *anyPersistent = 1u;
        const unsigned long long key = pairKey(old.geomA[j], old.geomB[j]);
        const unsigned int at = lowerBound(fresh.geomA, fresh.geomB, fresh.n, key);
        m = !(at < fresh.n && pairKey(fresh.geomA[at], fresh.geomB[at]) == key);
    }
    missing[j] = m;
}

// One thread per pair of the fresh set, then per pair of the old set: each goes to its place in the
// merged set, which is its index in its own set plus the number of pairs of the other set before it
// (the two sets share no key: a missing pair is one the fresh set lacks). missingBefore is the
// exclusive sum of deme_persistent_missing's flags.
extern "C" __global__ void deme_persistent_merge(ContactKeys fresh, const uint8_t* freshType, ContactKeys old,
                                                 const uint8_t* oldType, const unsigned int* missing,
                                                 const unsigned int* missingBefore, bodyID_t* outA, bodyID_t* outB,
                                                 uint8_t* outType) {
    const size_t t = globalIndex();
    if (t < fresh.n) {
        const unsigned int i = (unsigned int)t;
        const unsigned int lo = lowerBound(old.geomA, old.geomB, old.n, pairKey(fresh.geomA[i], fresh.geomB[i]));
        const unsigned int at = i + missingBefore[lo];
        outA[at] = fresh.geomA[i];
        outB[at] = fresh.geomB[i];
        outType[at] = freshType[i];
    } else if (t < (size_t)fresh.n + old.n) {
        const unsigned int j = (unsigned int)(t - fresh.n);
        if (!missing[j]) return;
        const unsigned int at =
            missingBefore[j] + lowerBound(fresh.geomA, fresh.geomB, fresh.n, pairKey(old.geomA[j], old.geomB[j]));
        outA[at] = old.geomA[j];
        outB[at] = old.geomB[j];
        outType[at] = oldType[j];
    }
}

// After history mapping: the persistent flag of each pair of the new set (oldPersistent may be null:
// none was persistent), and the family initial values of the wildcards of pairs new to the set.
// `s` is for the geometries' owners and families.
extern "C" __global__ void deme_persistent_flags(StateView s, ContactKeys fresh, const uint8_t* freshType,
                                                 ContactKeys old, const uint8_t* oldPersistent,
                                                 uint8_t* freshPersistent, const ContactInitRule* rules,
                                                 unsigned int numRules, float* freshWildcards, unsigned int W) {
    const size_t t = globalIndex();
    if (t >= fresh.n) return;
    const unsigned int i = (unsigned int)t;
    const unsigned long long key = pairKey(fresh.geomA[i], fresh.geomB[i]);
    const unsigned int lo = lowerBound(old.geomA, old.geomB, old.n, key);
    const bool found = lo < old.n && pairKey(old.geomA[lo], old.geomB[lo]) == key;
    freshPersistent[i] = found && oldPersistent ? oldPersistent[lo] : (uint8_t)0;
    if (found || numRules == 0) return;
    const family_t fa = s.owners.family[s.spheres.owner[fresh.geomA[i]]];
    const family_t fb = s.owners.family[geometryOwner(s, freshType[i], fresh.geomB[i])];
    for (unsigned int r = 0; r < numRules; r++) {
        const ContactInitRule& rule = rules[r];
        if ((rule.a == fa && rule.b == fb) || (rule.a == fb && rule.b == fa))
            freshWildcards[(size_t)i * W + rule.index] = rule.value;
    }
}

}  // namespace deme
