// Contact history across a re-detection on the GPU: the per-pair rules of kinematics/HistoryRules.h,
// one thread per pair (DeviceHistoryMapping runs them on dT's stream when dT installs a set).
//   1. deme_persistent_missing: which persistent pairs of the old set the new detection lacks;
//   2. deme_persistent_merge: the new set with those pairs merged in, still in key order;
//   3. deme_map_history: wildcards, mesh state and persistent flag of every pair of the new set.
// Compiled at run time by NVRTC.
#include "kinematics/HistoryRules.h"
#include "state/StateView.h"

namespace deme {

namespace {

__device__ inline size_t globalIndex() { return (size_t)blockIdx.x * blockDim.x + threadIdx.x; }

}  // namespace

// *anyPersistent = 1 if the old set has a persistent pair; where `missing` is given (nOld + 1
// entries, the last left 0 for the exclusive sum), missing[j] = 1 for a persistent pair j of the old
// set that the new set lacks. Launched without `missing` first: a set with no persistent pair needs
// no per-pair scratch.
extern "C" __global__ void deme_persistent_missing(ContactKeys fresh, ContactKeys old, const uint8_t* oldPersistent,
                                                   unsigned int* missing, unsigned int* anyPersistent) {
    const size_t j = globalIndex();
    if (j >= old.n) return;
    if (oldPersistent[j]) *anyPersistent = 1u;
    if (missing) missing[j] = persistentPairMissing(fresh, old, oldPersistent, (unsigned int)j) ? 1u : 0u;
}

// One thread per pair of the fresh set, then per pair of the old set: each goes to its place in the
// merged set. missingBefore is the exclusive sum of deme_persistent_missing's flags.
extern "C" __global__ void deme_persistent_merge(ContactKeys fresh, ContactKeys old, const unsigned int* missing,
                                                 const unsigned int* missingBefore, bodyID_t* outA, bodyID_t* outB) {
    const size_t t = globalIndex();
    if (t < fresh.n) {
        const unsigned int i = (unsigned int)t;
        const unsigned int at = mergedSlotOfFresh(fresh, old, missingBefore, i);
        outA[at] = fresh.geomA[i];
        outB[at] = fresh.geomB[i];
    } else if (t < (size_t)fresh.n + old.n) {
        const unsigned int j = (unsigned int)(t - fresh.n);
        if (!missing[j]) return;
        const unsigned int at = mergedSlotOfOld(fresh, old, missingBefore, j);
        outA[at] = old.geomA[j];
        outB[at] = old.geomB[j];
    }
}

// The history of every pair of the new set. `s` is for the geometries' owners and families.
extern "C" __global__ void deme_map_history(StateView s, ContactKeys fresh, OldContactHistory old,
                                            float* freshWildcards, uint8_t* freshMeshState, uint8_t* freshPersistent) {
    const size_t t = globalIndex();
    if (t >= fresh.n) return;
    const unsigned int i = (unsigned int)t;
    carryPairHistory(s, fresh, old, i, freshWildcards + (size_t)i * old.W, freshMeshState[i], freshPersistent[i]);
}

}  // namespace deme
