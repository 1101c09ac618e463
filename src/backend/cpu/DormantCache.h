// The CPU detector's cache of dormant spheres (the active box, docs/active-box.md): which spheres
// move, and the dormant ones registered by centre bin (kinematics/DormantRules.h). Rebuilt only when
// the owners' families differ from the ones it was built for (a family change, ChangeFamilyWhen,
// SetFamily) or after setGeometry (a host edit: positions, masks, prescriptions); every other
// detection bins and searches the moving spheres only.
#pragma once

#include <vector>

#include "runtime/MemoryAccounting.h"
#include "kinematics/DormantRules.h"
#include "state/SimState.h"

namespace deme {

class DormantCache {
  public:
    // 1 per dormant family (runtime/FamilyRules::dormantFamilies), 1 per family with a prescribed
    // velocity; `live` (the full host state, after Initialize or an edit) says which wall and mesh
    // owners can move: forces move them, their family prescribes a velocity, or they have one (a
    // kinematic owner keeps its velocity). Drops what was built.
    void setFamilies(const uint8_t* dormant, const uint8_t* prescribed, const SimState& live);
    void invalidate() { m_valid = false; }

    // Whether detection of `s` may use the cache: there are dormant spheres, and no geometry that
    // can move (a mesh or analytical owner with a velocity, a prescription or forces) has contacts
    // enabled with a dormant family, since such pairs would have to be searched from the dormant
    // side. Rebuilds the registry first if the families changed. Pairs of a dormant sphere with a
    // still wall or mesh are left out: neither side can move.
    bool prepare(const SimState& s, const BinGrid& grid, const uint8_t* familyMask, const float* familyExtraMargin);

    const std::vector<bodyID_t>& moving() const { return m_moving; }  // ascending sphere ids
    DormantBinsView view() const { return DormantBinsView{m_start.data(), m_items.data(), m_maxReach}; }
    size_t rebuilds() const { return m_rebuilds; }
    size_t bytes() const {
        return vectorBytes(m_movingWalls) + vectorBytes(m_builtFor) + vectorBytes(m_moving) + vectorBytes(m_start) +
               vectorBytes(m_items);
    }

  private:
    void rebuild(const SimState& s, const BinGrid& grid, const float* familyExtraMargin);

    uint8_t m_dormant[NUM_FAMILIES] = {};
    std::vector<bodyID_t> m_movingWalls;  // wall and mesh owners that can move
    bool m_anyDormantFamily = false;
    bool m_valid = false;
    std::vector<family_t> m_builtFor;  // owner families at the last rebuild
    std::vector<bodyID_t> m_moving;
    std::vector<uint32_t> m_start, m_items;
    double m_maxReach = 0.0;
    size_t m_rebuilds = 0;
};

}  // namespace deme
