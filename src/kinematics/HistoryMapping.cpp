#include "kinematics/HistoryMapping.h"

#include <algorithm>

#include "backend/cpu/Parallel.h"

namespace deme {

void installDetectedContacts(SimState& s, DetectedContacts& fresh) {
    ContactArrays& c = s.contacts;
    const size_t nOld = c.size();
    const size_t nNew = fresh.size();
    const unsigned int W = s.numWildcards;

    std::vector<uint64_t> oldKeys(nOld);
    for (size_t i = 0; i < nOld; i++) oldKeys[i] = contactKey(c.geomA[i], c.geomB[i]);

    std::vector<float> wildcards(nNew * W, 0.f);
    std::vector<uint8_t> meshState(nNew, 0);
#pragma omp parallel for schedule(static) if (nNew > PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < nNew; i++) {
        const uint64_t key = contactKey(fresh.geomA[i], fresh.geomB[i]);
        const auto it = std::lower_bound(oldKeys.begin(), oldKeys.end(), key);
        if (it != oldKeys.end() && *it == key) {
            const size_t j = (size_t)(it - oldKeys.begin());
            for (unsigned int w = 0; w < W; w++) wildcards[i * W + w] = c.wildcards[j * W + w];
            meshState[i] = c.meshState[j];
        }
    }
    c.geomA.swap(fresh.geomA);
    c.geomB.swap(fresh.geomB);
    c.type.swap(fresh.type);
    c.wildcards.swap(wildcards);
    c.meshState.swap(meshState);
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
