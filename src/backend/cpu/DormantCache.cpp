#include "backend/cpu/DormantCache.h"

#include <algorithm>
#include <cstring>

namespace deme {

void DormantCache::setFamilies(const uint8_t* dormant, const uint8_t* prescribed, const SimState& live) {
    std::memcpy(m_dormant, dormant, NUM_FAMILIES);
    m_anyDormantFamily = std::any_of(m_dormant, m_dormant + NUM_FAMILIES, [](uint8_t d) { return d != 0; });
    // The registry's searches know no periodic images: with periodic axes everything is searched.
    if (live.frame.periodic.axes) m_anyDormantFamily = false;
    m_valid = false;
    m_movingWalls.clear();
    auto note = [&](bodyID_t o) {
        if (ownerCanMove(live, prescribed, o) && (m_movingWalls.empty() || m_movingWalls.back() != o))
            m_movingWalls.push_back(o);
    };
    for (size_t k = 0; k < live.analytical.size(); k++) note(live.analytical.owner[k]);
    for (size_t t = 0; t < live.triangles.size(); t++) note(live.triangles.owner[t]);
}

bool DormantCache::prepare(const SimState& s, const BinGrid& grid, const uint8_t* familyMask,
                           const float* familyExtraMargin) {
    if (!m_anyDormantFamily) return false;
    const OwnerArrays& ow = s.owners;
    // A wall or mesh that can move must not reach a dormant family (with its family now).
    for (const bodyID_t o : m_movingWalls)
        if (movingFamilyReachesDormant(m_dormant, familyMask, ow.family[o])) return false;
    if (!m_valid || m_builtFor.size() != ow.family.size() ||
        std::memcmp(m_builtFor.data(), ow.family.data(), ow.family.size() * sizeof(family_t)) != 0)
        rebuild(s, grid, familyExtraMargin);
    return !m_items.empty();
}

void DormantCache::rebuild(const SimState& s, const BinGrid& grid, const float* familyExtraMargin) {
    m_rebuilds++;
    const size_t nS = s.spheres.size();
    const size_t nBins = (size_t)grid.numBins();
    m_builtFor = s.owners.family;
    m_moving.clear();
    m_start.assign(nBins + 1, 0);
    m_maxReach = 0.0;
    std::vector<uint32_t> binOf(nS);
    for (size_t i = 0; i < nS; i++) {
        if (!sphereIsDormant(s, m_dormant, i)) {
            m_moving.push_back((bodyID_t)i);
            continue;
        }
        const uint32_t b = dormantBinOf(s, grid, i);
        binOf[i] = b;
        m_start[(size_t)b + 1]++;
        m_maxReach = std::max(m_maxReach, dormantReachOf(s, familyExtraMargin, i));
    }
    for (size_t b = 0; b < nBins; b++) m_start[b + 1] += m_start[b];
    m_items.resize(m_start[nBins]);
    std::vector<uint32_t> fill(m_start.begin(), m_start.end() - 1);
    for (size_t i = 0; i < nS; i++)
        if (sphereIsDormant(s, m_dormant, i)) m_items[fill[binOf[i]]++] = (uint32_t)i;
    m_valid = true;
}

}  // namespace deme
