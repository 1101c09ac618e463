// Contact detection with dormant spheres (the active box, docs/active-box.md), written once for the
// CPU's loops (backend/cpu/DormantCache.cpp) and any GPU kernel over the same registry.
//
// A dormant sphere belongs to a dormant family (runtime/FamilyRules::dormantFamilies: fixed, no
// contacts with any fixed family): it never moves and never pairs with another dormant sphere, so
// its pairs are all with moving geometry and are found from the moving side. Dormant spheres are
// registered once, each in the one bin that holds its centre, and that registry serves every
// detection until the set of dormant spheres changes; a margin of any size needs no re-binning,
// because the moving sphere's search box grows by the largest dormant reach instead.
//
// No-miss: a dormant sphere b touches moving sphere a within the margins when |pA - pB| < eA + eB.
// Since eB <= maxDormantReach + margin, pB lies in the box pA +- (eA + maxDormantReach + margin),
// whose bins are searched; each dormant sphere is in exactly one bin, so each pair is found once.
#pragma once

#include "kinematics/DetectionRules.h"
#include "state/SphereLayout.h"

namespace deme {

// Dormant spheres by centre bin: bin b's are items[start[b] .. start[b + 1]), ascending.
struct DormantBinsView {
    const uint32_t *start, *items;
    double maxReach;  // largest radius + family extra margin of a dormant sphere (margin excluded)
};

// Whether sphere i is dormant (its owner's family is, `dormant`: 1 per family).
template <class S>
DEME_HD_INLINE bool sphereIsDormant(const S& s, const uint8_t* dormant, size_t i) {
    return dormant[s.owners.family[sphereOwner(s, i)]] != 0;
}

// The registry's key of dormant sphere i: the bin that holds its centre.
template <class S>
DEME_HD_INLINE uint32_t dormantBinOf(const S& s, const BinGrid& g, size_t i) {
    const double3 p = sphereCentre(s, i);
    return (uint32_t)binIndex(g, binCoord(g, 0, p.x), binCoord(g, 1, p.y), binCoord(g, 2, p.z));
}

// How far dormant sphere i reaches beyond its centre, the detection margin excluded.
template <class S>
DEME_HD_INLINE double dormantReachOf(const S& s, const float* familyExtraMargin, size_t i) {
    return (double)s.spheres.radius[i] + (double)familyExtraMargin[s.owners.family[sphereOwner(s, i)]];
}

// Whether owner o can move (of a wall or mesh: whether it could reach a dormant grain): forces move
// it, its family prescribes a velocity (`prescribed`: 1 per family), or it has a velocity (a
// kinematic owner keeps its own).
template <class S>
DEME_HD_INLINE bool ownerCanMove(const S& s, const uint8_t* prescribed, size_t o) {
    return s.massProps.dynamic[s.owners.inertia[o]] != 0 || prescribed[s.owners.family[o]] ||
           dot(s.owners.vel[o], s.owners.vel[o]) > 0.f || dot(s.owners.angVel[o], s.owners.angVel[o]) > 0.f;
}

// Whether a wall or mesh owner that can move, now of family f, forbids the registry: it has contacts
// enabled with a dormant family, so those pairs would have to be searched from the dormant side.
DEME_HD_INLINE bool movingFamilyReachesDormant(const uint8_t* dormant, const uint8_t* familyMask, unsigned int f) {
    if (dormant[f]) return false;
    for (unsigned int g = 0; g < NUM_FAMILIES; g++)
        if (dormant[g] && familyMask[(size_t)f * NUM_FAMILIES + g]) return true;
    return false;
}

// Dormant partners of moving sphere sa (sphere ids, any order) into out[0, capacity); returns how
// many there are (if more than capacity, call again with room for all).
template <class S>
DEME_HD_INLINE unsigned int dormantPartners(const S& s, const DetectionArgs& a, const DormantBinsView& d, bodyID_t sa,
                                            bodyID_t* out, unsigned int capacity) {
    const BinGrid& g = a.grid;
    const double3 pA = sphereCentre(s, sa);
    const bodyID_t oA = sphereOwner(s, sa);
    const double eA = (double)s.spheres.radius[sa] + marginOf(s, a, oA);
    const double R = eA + d.maxReach + a.margin;
    const BinBox box =
        binBox(g, make_double3(pA.x - R, pA.y - R, pA.z - R), make_double3(pA.x + R, pA.y + R, pA.z + R));
    const uint8_t* maskRow = a.familyMask + (size_t)s.owners.family[oA] * NUM_FAMILIES;
    // A row of bins along x holds its entries one after the other (bins are numbered x fastest and
    // each dormant sphere is in one bin), so a row is one range of entries: its two ends are read
    // once instead of each bin's. Along a periodic x the row would wrap: bin by bin there.
    const bool rows = !(g.periodic & 1u);
    const bool shared = a.sharedExtraMargin >= 0.0;
    unsigned int n = 0;
    for (int z = box.lo[2]; z <= box.hi[2]; z++)
        for (int y = box.lo[1]; y <= box.hi[1]; y++)
            for (int x = box.lo[0]; x <= box.hi[0]; x++) {
                const uint64_t bin = binIndex(g, x, y, z);
                const uint64_t last = rows ? binIndex(g, box.hi[0], y, z) : bin;
                for (uint32_t e = d.start[bin]; e < d.start[last + 1]; e++) {
                    // Distance first (b's position and radius only); owner and family for the rest.
                    const bodyID_t b = d.items[e];
                    const double3 dd = pA - sphereCentre(s, b);
                    const double rB = (double)s.spheres.radius[b];
                    const bodyID_t oB0 = shared ? 0 : sphereOwner(s, b);
                    const double reach = eA + rB + (shared ? a.margin + a.sharedExtraMargin : marginOf(s, a, oB0));
                    if (dot(dd, dd) >= reach * reach) continue;
                    const bodyID_t oB = shared ? sphereOwner(s, b) : oB0;
                    if (!maskRow[s.owners.family[oB]]) continue;
                    if (n < capacity) out[n] = b;
                    n++;
                }
                if (rows) break;  // the row's entries are done
            }
    return n;
}

}  // namespace deme
