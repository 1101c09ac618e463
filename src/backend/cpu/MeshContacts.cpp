#include "backend/cpu/MeshContacts.h"

#include <algorithm>

#include "parallel/Parallel.h"
#include "dynamics/MeshContactRule.h"

namespace deme {

void resolveMeshContacts(SimState& s) {
    const ContactArrays& c = s.contacts;
    const std::vector<uint32_t>& groups = c.meshContactGroups;
    if (groups.size() < 2) return;
    const size_t nGroups = groups.size() - 1;
    size_t largest = 0;
    for (size_t g = 0; g < nGroups; g++) largest = std::max<size_t>(largest, groups[g + 1] - groups[g]);
#pragma omp parallel if (nGroups > PARALLEL_MIN_ITEMS / 8)
    {
        std::vector<MeshCandidate> cand(largest);
#pragma omp for schedule(static)
        for (size_t g = 0; g < nGroups; g++)
            resolveSphereMeshContacts(s, c.meshContacts[groups[g]], groups[g + 1] - groups[g], cand.data(), largest);
    }
}

}  // namespace deme
