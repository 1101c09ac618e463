#include "backend/cpu/MeshContacts.h"

#include <algorithm>

#include "parallel/Parallel.h"
#include "dynamics/MeshContactRule.h"

namespace deme {

namespace {

// A sphere-triangle pair's slot in the pooled form (every such pair has one: backend/cpu/HistoryForm.h).
struct HistoryInPool {
    PooledHistory* pool;
    uint8_t* meshStates;
    unsigned int W;
    float* operator()(size_t i) const { return pool->values.data() + (size_t)pool->slotOf(i) * W; }
    uint8_t& meshState(size_t i) const { return meshStates[i]; }
};

}  // namespace

void resolveMeshContacts(SimState& s) {
    ContactArrays& c = s.contacts;
    const unsigned int W = s.numWildcards;
    const bool pooled = c.historyPooled(W);
    const std::vector<uint32_t>& groups = c.meshContactGroups;
    if (groups.size() < 2) return;
    const size_t nGroups = groups.size() - 1;
    size_t largest = 0;
    for (size_t g = 0; g < nGroups; g++) largest = std::max<size_t>(largest, groups[g + 1] - groups[g]);
#pragma omp parallel if (nGroups > PARALLEL_MIN_ITEMS / 8)
    {
        std::vector<MeshCandidate> cand(largest);
#pragma omp for schedule(static)
        for (size_t g = 0; g < nGroups; g++) {
            const uint32_t first = c.meshContacts[groups[g]], n = groups[g + 1] - groups[g];
            const bodyID_t a = c.pairA(first);
            if (pooled)
                resolveSphereMeshContactsWith(s, a, first, n, cand.data(), largest,
                                              HistoryInPool{&c.pooled, c.meshState.data(), W});
            else
                resolveSphereMeshContactsWith(s, a, first, n, cand.data(), largest,
                                              HistoryInSet{c.wildcards.data(), c.meshState.data(), W});
        }
    }
}

}  // namespace deme
