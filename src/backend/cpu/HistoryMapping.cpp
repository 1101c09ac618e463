#include "backend/cpu/HistoryMapping.h"

#include <algorithm>

#include "backend/cpu/ForcePass.h"
#include "kinematics/HistoryRules.h"
#include "parallel/Parallel.h"
#include "runtime/MemoryAccounting.h"

namespace deme {

namespace {

ContactKeys keysOf(const std::vector<bodyID_t>& geomA, const std::vector<bodyID_t>& geomB) {
    return ContactKeys{geomA.data(), geomB.data(), (unsigned int)geomA.size()};
}

// Adds to `fresh` the persistent pairs of the current set that it lacks, keeping it sorted by key.
void mergePersistentPairs(const ContactArrays& c, DetectedContacts& fresh) {
    const ContactKeys old = keysOf(c.geomA, c.geomB), freshKeys = keysOf(fresh.geomA, fresh.geomB);
    const size_t nOld = old.n, nFresh = freshKeys.n;
    std::vector<unsigned int> missingBefore(nOld + 1, 0);
#pragma omp parallel for schedule(static) if (nOld > PARALLEL_MIN_ITEMS)
    for (size_t j = 0; j < nOld; j++)
        missingBefore[j] = persistentPairMissing(freshKeys, old, c.persistent.data(), (unsigned int)j) ? 1u : 0u;
    std::vector<uint8_t> missing(missingBefore.begin(), missingBefore.end() - 1);
    unsigned int sum = 0;
    for (unsigned int& m : missingBefore) {
        const unsigned int v = m;
        m = sum;
        sum += v;
    }
    if (sum == 0) return;
    DetectedContacts merged;
    merged.geomA.resize(nFresh + sum);
    merged.geomB.resize(nFresh + sum);
    merged.type.resize(nFresh + sum);
#pragma omp parallel for schedule(static) if (nFresh > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < nFresh; i++) {
        const unsigned int at = mergedSlotOfFresh(freshKeys, old, missingBefore.data(), (unsigned int)i);
        merged.geomA[at] = fresh.geomA[i];
        merged.geomB[at] = fresh.geomB[i];
        merged.type[at] = fresh.type[i];
    }
    for (size_t j = 0; j < nOld; j++) {
        if (!missing[j]) continue;
        const unsigned int at = mergedSlotOfOld(freshKeys, old, missingBefore.data(), (unsigned int)j);
        merged.geomA[at] = c.geomA[j];
        merged.geomB[at] = c.geomB[j];
        merged.type[at] = c.type[j];
    }
    fresh = std::move(merged);
}

}  // namespace

void installDetectedContacts(SimState& s, DetectedContacts& fresh) {
    ContactArrays& c = s.contacts;
    const unsigned int W = s.numWildcards;
    // The old set's reduction index and stored forces are rebuilt for the new set below: emptied,
    // and let go where large, before the new set's arrays are made, while the old set's pairs and
    // history are still held (an installation's peak).
    c.resetIndex();
    const bool anyPersistent = std::find(c.persistent.begin(), c.persistent.end(), 1) != c.persistent.end();
    if (anyPersistent) mergePersistentPairs(c, fresh);
    const size_t nNew = fresh.size();
    const OldContactHistory old{keysOf(c.geomA, c.geomB),
                                c.wildcards.data(),
                                c.meshState.data(),
                                anyPersistent ? c.persistent.data() : nullptr,
                                W,
                                s.wildcards.contactInit.data(),
                                (unsigned int)s.wildcards.contactInit.size()};
    const ContactKeys freshKeys = keysOf(fresh.geomA, fresh.geomB);
    std::vector<float> wildcards(nNew * W);
    std::vector<uint8_t> meshState(nNew), persistent(nNew);
#pragma omp parallel for schedule(static) if (nNew > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < nNew; i++)
        carryPairHistory(s, freshKeys, fresh.type.data(), old, (unsigned int)i, wildcards.data() + i * W, meshState[i],
                         persistent[i]);
    c.geomA.swap(fresh.geomA);
    c.geomB.swap(fresh.geomB);
    c.type.swap(fresh.type);
    c.wildcards.swap(wildcards);
    c.meshState.swap(meshState);
    c.persistent.swap(persistent);
    // `fresh` now holds the old set's ids, and the locals its history (swapped out above):
    // released, not kept until the next detection (9 B per pair of the set for the whole run,
    // docs/memory.md), nor through the indexing below (18 B per pair more at the peak).
    fresh = DetectedContacts();
    releaseVector(wildcards);
    releaseVector(meshState);
    releaseVector(persistent);
    indexContactSet(s);
}

void indexContactSet(SimState& s) {
    ContactArrays& c = s.contacts;
    const size_t nNew = c.size();
    // Whatever was indexed for another set (before a checkpoint was read into this one, forces
    // stored for it) is emptied: an installation has done so already, before its new arrays.
    c.resetIndex();
    for (size_t i = 0; i < nNew; i++) {
        if (c.type[i] != SPHERE_TRIANGLE) continue;
        if (c.meshContacts.empty() || c.geomA[c.meshContacts.back()] != c.geomA[i])
            c.meshContactGroups.push_back((uint32_t)c.meshContacts.size());
        c.meshContacts.push_back((uint32_t)i);
    }
    c.meshContactGroups.push_back((uint32_t)c.meshContacts.size());
    buildOwnerContactIndex(s);
}

}  // namespace deme
