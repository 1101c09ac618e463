#include "backend/cuda/DeviceDormantRegistry.h"

#include "runtime/FamilyRules.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;

}  // namespace

DormantFamilies DormantFamilies::of(const SimState& live, const FamilyRules& families) {
    DormantFamilies f;
    families.dormantFamilies(f.dormant.data());
    uint8_t prescribed[NUM_FAMILIES];
    families.prescribedFamilies(prescribed);
    for (uint8_t d : f.dormant) f.any = f.any || d != 0;
    // The registry's searches know no periodic images: with periodic axes everything is searched.
    if (live.frame.periodic.axes) f.any = false;
    // Which walls and meshes move matters only to a registry (a byte per owner, on the host and
    // the GPU: none in a run without dormant families).
    if (!f.any) return f;
    f.movable.assign(live.owners.size(), 0);
    for (size_t k = 0; k < live.analytical.size(); k++) {
        const bodyID_t o = live.analytical.owner[k];
        f.movable[o] = ownerCanMove(live, prescribed, o) ? 1 : 0;
    }
    for (size_t t = 0; t < live.triangles.size(); t++) {
        const bodyID_t o = live.triangles.owner[t];
        f.movable[o] = ownerCanMove(live, prescribed, o) ? 1 : 0;
    }
    return f;
}

void DeviceDormantRegistry::loadKernels(const CudaModule& m) {
    m_kCheck = m.kernel("deme_dormant_check");
    m_kFlags = m.kernel("deme_dormant_flags");
    m_kScatter = m.kernel("deme_dormant_scatter");
    m_kBinCounts = m.kernel("deme_bin_counts");
    m_kPairKeys = m.kernel("deme_pair_keys");
    m_kPairsFromKeys = m.kernel("deme_pairs_from_keys");
}

void DeviceDormantRegistry::upload(const DormantFamilies& f, Stream stream) {
    m_any = f.any;
    m_valid = false;
    uploadResized(m_dormant, f.dormant, stream);
    uploadResized(m_movable, f.movable, stream);
}

bool DeviceDormantRegistry::prepare(const StateView& v, const BinGrid& grid, const DeviceBuffer<family_t>& ownerFamily,
                                    size_t numOwners, const uint8_t* familyMask, const float* familyExtraMargin,
                                    DevicePrimitives& prim, Stream stream) {
    if (!m_any || v.numSpheres == 0) return false;
    // flags: [0] families changed since the rebuild, [1] a movable wall or mesh reaches a dormant family.
    unsigned int flags[2] = {0u, 0u};
    m_flags.resizeDiscarding(2);
    m_flags.zeroAsync(stream);
    if (m_valid && m_builtFor.size() == numOwners && numOwners) {
        launch(m_kCheck, blocksFor(numOwners, THREADS), THREADS, 0, stream, v, (const family_t*)m_builtFor.data(),
               (const uint8_t*)m_movable.data(), (const uint8_t*)m_dormant.data(), familyMask, m_flags.data());
    } else {
        flags[0] = 1u;
        if (numOwners)
            launch(m_kCheck, blocksFor(numOwners, THREADS), THREADS, 0, stream, v, ownerFamily.data(),
                   (const uint8_t*)m_movable.data(), (const uint8_t*)m_dormant.data(), familyMask, m_flags.data());
    }
    unsigned int found[2] = {0u, 0u};
    m_flags.downloadAsync(found, 2, stream);
    synchronize(stream);
    if (found[1]) return false;  // searched whole, as without the box (correct, not cached)
    if (flags[0] || found[0]) rebuild(v, grid, ownerFamily, numOwners, familyExtraMargin, prim, stream);
    return m_numDormant > 0;
}

void DeviceDormantRegistry::rebuild(const StateView& v, const BinGrid& grid, const DeviceBuffer<family_t>& ownerFamily,
                                    size_t numOwners, const float* familyExtraMargin, DevicePrimitives& prim,
                                    Stream stream) {
    m_rebuilds++;
    const unsigned int nS = v.numSpheres;
    const uint64_t numBins = grid.numBins();
    m_builtFor.resizeDiscarding(numOwners);
    m_builtFor.copyFromAsync(ownerFamily, numOwners, stream);
    // 1. Which spheres move and which are dormant, and the dormant reach.
    m_isMoving.resizeDiscarding(nS + 1);
    m_isDormant.resizeDiscarding(nS + 1);
    m_movingOffset.resizeDiscarding(nS + 1);
    m_dormantOffset.resizeDiscarding(nS + 1);
    m_reach.resizeDiscarding(nS);
    m_maxReachDev.resizeDiscarding(1);
    m_isMoving.zeroAsync(stream);
    m_isDormant.zeroAsync(stream);
    launch(m_kFlags, blocksFor(nS, THREADS), THREADS, 0, stream, v, (const uint8_t*)m_dormant.data(), familyExtraMargin,
           m_isMoving.data(), m_isDormant.data(), m_reach.data());
    prim.exclusiveSum(m_isMoving.data(), m_movingOffset.data(), nS + 1, stream);
    prim.exclusiveSum(m_isDormant.data(), m_dormantOffset.data(), nS + 1, stream);
    prim.reduceMax(m_reach.data(), m_maxReachDev.data(), nS, stream);
    unsigned int counts[2] = {0u, 0u};
    m_movingOffset.downloadAsync(&counts[0], 1, stream, nS);
    m_dormantOffset.downloadAsync(&counts[1], 1, stream, nS);
    m_maxReachDev.downloadAsync(&m_maxReach, 1, stream);
    synchronize(stream);
    m_numMoving = counts[0];
    m_numDormant = counts[1];
    // 2. The moving list, and the dormant spheres' (centre bin, sphere) entries sorted by bin.
    m_moving.resizeDiscarding(m_numMoving);
    m_keys.resizeDiscarding(m_numDormant);
    m_items.resizeDiscarding(m_numDormant);
    m_sortedKeys.resizeDiscarding(m_numDormant);
    m_sortedItems.resizeDiscarding(m_numDormant);
    launch(m_kScatter, blocksFor(nS, THREADS), THREADS, 0, stream, v, grid, (const uint8_t*)m_dormant.data(),
           (const unsigned int*)m_movingOffset.data(), (const unsigned int*)m_dormantOffset.data(), m_moving.data(),
           m_keys.data(), m_items.data());
    if (m_numDormant)
        prim.sortPairs(m_keys.data(), m_sortedKeys.data(), m_items.data(), m_sortedItems.data(), m_numDormant, stream,
                       0, bitsFor(numBins));
    // 3. Each bin's first entry: the entries per bin, summed (in place).
    m_start.resizeDiscarding(numBins + 1);
    m_start.zeroAsync(stream);
    if (m_numDormant)
        launch(m_kBinCounts, blocksFor(m_numDormant, THREADS), THREADS, 0, stream, (const unsigned int*)m_keys.data(),
               m_numDormant, m_start.data());
    prim.exclusiveSum(m_start.data(), m_start.data(), numBins + 1, stream);
    synchronize(stream);
    m_valid = true;
}

void DeviceDormantRegistry::sortPairs(const StateView& v, bodyID_t* geomA, bodyID_t* geomB, unsigned int n,
                                      DevicePrimitives& prim, Stream stream) {
    if (n == 0) return;
    // A is a sphere; B any geometry (unified ids).
    const int aBits = bitsFor(v.numSpheres);
    const int bBits = bitsFor((unsigned long long)v.triangleIdBase() + v.numTriangles);
    m_pairKeys.resizeDiscarding(n);
    m_pairKeysSorted.resizeDiscarding(n);
    m_pairIdx.resizeDiscarding(n);
    m_pairIdxSorted.resizeDiscarding(n);
    launch(m_kPairKeys, blocksFor(n, THREADS), THREADS, 0, stream, (const bodyID_t*)geomA, (const bodyID_t*)geomB, n,
           bBits, (unsigned long long*)m_pairKeys.data(), m_pairIdx.data());
    prim.sortPairs(m_pairKeys.data(), m_pairKeysSorted.data(), m_pairIdx.data(), m_pairIdxSorted.data(), n, stream, 0,
                   aBits + bBits);
    launch(m_kPairsFromKeys, blocksFor(n, THREADS), THREADS, 0, stream,
           (const unsigned long long*)m_pairKeysSorted.data(), n, bBits, geomA, geomB);
}

}  // namespace deme::cuda
