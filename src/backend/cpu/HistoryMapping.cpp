#include "backend/cpu/HistoryMapping.h"

#include <algorithm>

#include "parallel/Parallel.h"
#include "dynamics/ContactInputsGather.h"

namespace deme {

namespace {

std::vector<uint64_t> keysOf(const std::vector<bodyID_t>& geomA, const std::vector<bodyID_t>& geomB) {
    std::vector<uint64_t> keys(geomA.size());
    for (size_t i = 0; i < keys.size(); i++) keys[i] = contactKey(geomA[i], geomB[i]);
    return keys;
}

// Adds to `fresh` the persistent pairs of the current set that it lacks, keeping it sorted by key.
void keepPersistentPairs(const SimState& s, const std::vector<uint64_t>& oldKeys, DetectedContacts& fresh,
                         std::vector<uint64_t>& freshKeys) {
    const ContactArrays& c = s.contacts;
    std::vector<size_t> missing;  // indices into the current set, in key order
    for (size_t j = 0; j < oldKeys.size(); j++)
        if (c.persistent[j] && !std::binary_search(freshKeys.begin(), freshKeys.end(), oldKeys[j]))
            missing.push_back(j);
    if (missing.empty()) return;
    DetectedContacts merged;
    const size_t n = fresh.size() + missing.size();
    merged.geomA.reserve(n);
    merged.geomB.reserve(n);
    merged.type.reserve(n);
    size_t i = 0, k = 0;
    while (i < fresh.size() || k < missing.size()) {
        if (k == missing.size() || (i < fresh.size() && freshKeys[i] < oldKeys[missing[k]])) {
            merged.geomA.push_back(fresh.geomA[i]);
            merged.geomB.push_back(fresh.geomB[i]);
            merged.type.push_back(fresh.type[i]);
            i++;
        } else {
            const size_t j = missing[k++];
            merged.geomA.push_back(c.geomA[j]);
            merged.geomB.push_back(c.geomB[j]);
            merged.type.push_back(c.type[j]);
        }
    }
    fresh = std::move(merged);
    freshKeys = keysOf(fresh.geomA, fresh.geomB);
}

// Wildcards of a pair entering the set: 0, or the value set for its two families.
void initialWildcards(const SimState& s, bodyID_t a, bodyID_t b, uint8_t type, float* wc) {
    const family_t fa = s.owners.family[s.spheres.owner[a]];
    const family_t fb = s.owners.family[geometryOwner(s, type, b)];
    for (const WildcardArrays::ContactInit& r : s.wildcards.contactInit)
        if ((r.a == fa && r.b == fb) || (r.a == fb && r.b == fa)) wc[r.index] = r.value;
}

}  // namespace

void installDetectedContacts(SimState& s, DetectedContacts& fresh) {
    ContactArrays& c = s.contacts;
    const unsigned int W = s.numWildcards;
    const std::vector<uint64_t> oldKeys = keysOf(c.geomA, c.geomB);
    std::vector<uint64_t> freshKeys = keysOf(fresh.geomA, fresh.geomB);
    if (std::find(c.persistent.begin(), c.persistent.end(), 1) != c.persistent.end())
        keepPersistentPairs(s, oldKeys, fresh, freshKeys);
    const size_t nNew = fresh.size();
    const bool initRules = !s.wildcards.contactInit.empty();

    std::vector<float> wildcards(nNew * W, 0.f);
    std::vector<uint8_t> meshState(nNew, 0), persistent(nNew, 0);
#pragma omp parallel for schedule(static) if (nNew > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < nNew; i++) {
        const uint64_t key = freshKeys[i];
        const auto it = std::lower_bound(oldKeys.begin(), oldKeys.end(), key);
        if (it != oldKeys.end() && *it == key) {
            const size_t j = (size_t)(it - oldKeys.begin());
            for (unsigned int w = 0; w < W; w++) wildcards[i * W + w] = c.wildcards[j * W + w];
            meshState[i] = c.meshState[j];
            persistent[i] = c.persistent[j];
        } else if (initRules) {
            initialWildcards(s, fresh.geomA[i], fresh.geomB[i], fresh.type[i], wildcards.data() + i * W);
        }
    }
    c.geomA.swap(fresh.geomA);
    c.geomB.swap(fresh.geomB);
    c.type.swap(fresh.type);
    c.wildcards.swap(wildcards);
    c.meshState.swap(meshState);
    c.persistent.swap(persistent);
    c.meshContacts.clear();
    c.meshContactGroups.clear();
    for (size_t i = 0; i < nNew; i++) {
        if (c.type[i] != SPHERE_TRIANGLE) continue;
        if (c.meshContacts.empty() || c.geomA[c.meshContacts.back()] != c.geomA[i])
            c.meshContactGroups.push_back((uint32_t)c.meshContacts.size());
        c.meshContacts.push_back((uint32_t)i);
    }
    c.meshContactGroups.push_back((uint32_t)c.meshContacts.size());
    c.force.assign(nNew, make_float3(0.f));
    c.torqueA.assign(nNew, make_float3(0.f));
    c.torqueB.assign(nNew, make_float3(0.f));
}

}  // namespace deme
