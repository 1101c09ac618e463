// The GPU detector's registry of dormant spheres (the active box, docs/active-box.md), the device
// counterpart of backend/cpu/DormantCache.h with the same rules (kinematics/DormantRules.h, run by
// the kernels of kernels/Detection.cu): which spheres move (listed ascending), and the dormant ones
// by centre bin, sorted with CUB. Rebuilt on the device only when the owners' families differ from
// the ones it was built for (a check kernel compares them at each detection) or after the geometry
// was uploaded again (a host edit); every other detection bins and searches the moving spheres only.
// Also puts the pairs found from both sides into (A, B) order. Used by kT's thread only.
#pragma once

#include <vector>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DevicePrimitives.h"
#include "kinematics/DormantRules.h"
#include "state/SimState.h"
#include "state/StateView.h"

namespace deme {
class FamilyRules;
}

namespace deme::cuda {

// What the host knows at setGeometry: the dormant families and which owners (walls and meshes) can move.
struct DormantFamilies {
    std::vector<uint8_t> dormant = std::vector<uint8_t>(NUM_FAMILIES, 0);  // 1 per dormant family
    std::vector<uint8_t> movable;  // 1 per owner: a wall or mesh that can move (empty where none is dormant)
    bool any = false;
    static DormantFamilies of(const SimState& live, const FamilyRules& families);
};

class DeviceDormantRegistry {
  public:
    void loadKernels(const CudaModule& m);
    // Copies the families to the device (on `stream`) and drops what was built.
    void upload(const DormantFamilies& f, Stream stream);

    // Whether detection of `v` may use the registry (the rules of DormantCache::prepare), rebuilding
    // it first if the families changed. familyMask and familyExtraMargin are device pointers.
    bool prepare(const StateView& v, const BinGrid& grid, const DeviceBuffer<family_t>& ownerFamily, size_t numOwners,
                 const uint8_t* familyMask, const float* familyExtraMargin, DevicePrimitives& prim, Stream stream);

    const bodyID_t* moving() const { return m_moving.data(); }  // ascending sphere ids
    unsigned int numMoving() const { return m_numMoving; }
    DormantBinsView view() const { return DormantBinsView{m_start.data(), m_sortedItems.data(), m_maxReach}; }
    size_t rebuilds() const { return m_rebuilds; }

    // Pairs (geomA, geomB)[0, n) into (A, B) order (A a sphere of v, B any geometry).
    void sortPairs(const StateView& v, bodyID_t* geomA, bodyID_t* geomB, unsigned int n, DevicePrimitives& prim,
                   Stream stream);

  private:
    void rebuild(const StateView& v, const BinGrid& grid, const DeviceBuffer<family_t>& ownerFamily, size_t numOwners,
                 const float* familyExtraMargin, DevicePrimitives& prim, Stream stream);

    CudaKernel m_kCheck, m_kFlags, m_kScatter, m_kBinCounts, m_kPairKeys, m_kPairsFromKeys;
    bool m_any = false, m_valid = false;
    DeviceBuffer<uint8_t> m_dormant, m_movable;
    DeviceBuffer<family_t> m_builtFor;
    DeviceBuffer<unsigned int> m_flags, m_isMoving, m_isDormant, m_movingOffset, m_dormantOffset;
    DeviceBuffer<double> m_reach, m_maxReachDev;
    DeviceBuffer<bodyID_t> m_moving;
    DeviceBuffer<unsigned int> m_keys, m_items, m_sortedKeys, m_sortedItems, m_start;
    DeviceBuffer<uint64_t> m_pairKeys, m_pairKeysSorted;
    DeviceBuffer<uint32_t> m_pairIdx, m_pairIdxSorted;
    unsigned int m_numMoving = 0, m_numDormant = 0;
    double m_maxReach = 0.0;
    size_t m_rebuilds = 0;
};

}  // namespace deme::cuda
