// Contact detection (the kinematics side, paper §2.1) as per-item functions, written once for the
// CPU's OpenMP loops (backend/cpu/ContactDetector.cpp) and the GPU's kernels
// (backend/cuda/kernels/Detection.cu); templates over the state type (SimState or StateView, same
// member names). What differs between the backends is only how items are sorted into bins.
//
// Method: every geometry, enlarged by its margin, is registered in each bin its box touches; each
// sphere A then searches the bins of its box, and a pair is reported only from the bin that holds
// the lower corner of the two enlarged boxes' intersection, so exactly once. A sphere's partners
// come in contact-set order: spheres by id, analytical components by id, triangles by id. So the
// whole set is sorted by (A, B), which history mapping's binary searches need.
//
// Spheres by centre (DetectionArgs::centreReach > 0): where no sphere reaches far beyond a bin, each
// sphere is registered only in the bin of its centre (one entry instead of about eight), and A looks
// for its sphere partners B > A in the bins of its centre's box grown by the largest reach: every B
// within reach has its centre there, and is in one bin, so each pair is found once without the
// lower-corner rule. Triangles stay registered by their boxes and are searched as above. The same
// pairs either way (docs/memory.md, "Spheres binned by their centres").
//
// No-miss bound: every geometry is enlarged by `margin`. A pair left out is more than 2*margin apart.
// The step loop re-detects before any owner's accumulated travel (an upper bound on how far any of
// its surface points moved) exceeds the margin, so such a pair cannot touch before the next
// detection: the gap can shrink by at most travelA + travelB <= 2*margin.
#pragma once

#if !defined(__CUDACC_RTC__)
#include <cstdlib>
#endif

#include "kinematics/BinGrid.h"
#include "physics/ContactGeometry.h"
#include "physics/Periodic.h"
#include "state/SphereLayout.h"

namespace deme {

// Items registered in bins: the items of each bin (bin b's are items[start[b] .. start[b + 1]),
// ascending). Which bins an item covers is not stored: it follows from the item's box (sphereBinBox,
// triangleBinBox), computed where it is needed (24 bytes per sphere less than keeping it). A
// detection in slabs (kinematics/BinSlabs.h) holds one slab's bins, from bin firstBin on: `start`
// is indexed from there.
struct BinsView {
    const uint32_t *start, *items;
    uint64_t firstBin = 0;
    // Bin b's first entry and its end (the next bin's first).
    DEME_HD uint32_t first(uint64_t b) const { return start[b - firstBin]; }
    DEME_HD uint32_t end(uint64_t b) const { return start[b - firstBin + 1]; }
};

// What detection reads besides the state.
struct DetectionArgs {
    BinGrid grid;
    double margin;
    const float* familyExtraMargin;     // NUM_FAMILIES values added to each family's margin
    const uint8_t* familyMask;          // NUM_FAMILIES x NUM_FAMILIES, nonzero where contacts are resolved
    BinsView sphereBins, triangleBins;  // triangleBins.start is null where there are no triangles
    const double3 *triLo, *triHi;       // triangles' enlarged boxes
    // The extra margin of every family where all are equal (the usual case), else negative: then a
    // candidate's enlarged radius needs no lookup of its owner and family, which the pair search
    // does only for the candidates that pass the geometric tests.
    double sharedExtraMargin;
    // Above zero: spheres are registered by their centres (above), and no sphere's enlarged radius
    // (radius, margin and its family's extra margin) exceeds this. Zero: by their boxes.
    double centreReach = 0.0;
};

// The grid of a detection from a state whose periodic box is p: in a sheared cell its image layers
// are displaced by the offset at the state's time.
DEME_HD_INLINE BinGrid withShearOffset(BinGrid g, const PeriodicBox& p) {
    g.shearOffset = p.shear ? shearOffsetNow(p) : 0.0;
    return g;
}

#if !defined(__CUDACC_RTC__)
// DetectionArgs::sharedExtraMargin of the NUM_FAMILIES extra margins `extra`.
inline double sharedExtraMarginOf(const float* extra) {
    for (unsigned int f = 1; f < NUM_FAMILIES; f++)
        if (extra[f] != extra[0]) return -1.0;
    return (double)extra[0];
}

// DetectionArgs::centreReach for a detection with margin `margin` whose binned spheres' largest
// radius is maxRadius: their largest enlarged radius where they are registered by centre, else 0.
// By centre where no sphere reaches beyond 3/4 of a bin's edge: beyond, a centre's search box takes
// more bins than registering the boxes costs (a ball among grains would make every grain search
// the ball's reach). Not in a sheared cell, whose image layers register a box's bins shifted and
// one bin wider. DEME_BIN_BY_BOXES=1 registers by boxes always (for comparisons).
// (The same from the spheres' largest enlarged radius, `reach`: radius, margin and extra margin.)
inline double centreReachFor(const BinGrid& g, double reach) {
    if (const char* v = std::getenv("DEME_BIN_BY_BOXES"); v && v[0] == '1' && v[1] == 0) return 0.0;
    if (g.shear || !(reach > 0.0)) return 0.0;
    const double edge =
        g.edge.x < g.edge.y ? (g.edge.x < g.edge.z ? g.edge.x : g.edge.z) : (g.edge.y < g.edge.z ? g.edge.y : g.edge.z);
    return reach <= 0.75 * edge ? reach : 0.0;
}
inline double centreReachFor(const BinGrid& g, double margin, const float* extra, double maxRadius) {
    if (!(maxRadius > 0.0)) return 0.0;
    float largestExtra = extra[0];
    for (unsigned int f = 1; f < NUM_FAMILIES; f++) largestExtra = extra[f] > largestExtra ? extra[f] : largestExtra;
    return centreReachFor(g, maxRadius + margin + (double)largestExtra);
}
#endif

template <class S>
DEME_HD_INLINE double marginOf(const S& s, const DetectionArgs& a, bodyID_t owner) {
    return a.margin + (double)a.familyExtraMargin[s.owners.family[owner]];
}

// The box of half-width e about p: a sphere's, enlarged radius e, as registration and search take it.
DEME_HD_INLINE void boxAround(const double3& p, double e, double3& lo, double3& hi) {
    lo = make_double3(p.x - e, p.y - e, p.z - e);
    hi = make_double3(p.x + e, p.y + e, p.z + e);
}

// Sphere i's box, enlarged by its margin.
template <class S>
DEME_HD_INLINE void sphereBox(const S& s, const DetectionArgs& a, size_t i, double3& lo, double3& hi) {
    boxAround(sphereCentre(s, i), (double)s.spheres.radius[i] + marginOf(s, a, sphereOwner(s, i)), lo, hi);
}

// The one bin that holds point p (not widened: a point is registered once).
DEME_HD_INLINE BinBox pointBin(const BinGrid& g, const double3& p) {
    BinBox b;
    b.lo[0] = b.hi[0] = binCoord(g, 0, p.x);
    b.lo[1] = b.hi[1] = binCoord(g, 1, p.y);
    b.lo[2] = b.hi[2] = binCoord(g, 2, p.z);
    return b;
}

// The bins sphere i is registered in: those its enlarged box covers (registration and search
// compute them alike), or by centre the bin of its centre.
template <class S>
DEME_HD_INLINE BinBox sphereBinBox(const S& s, const DetectionArgs& a, size_t i) {
    if (a.centreReach > 0.0) return pointBin(a.grid, sphereCentre(s, i));
    double3 lo, hi;
    sphereBox(s, a, i, lo, hi);
    return binBox(a.grid, lo, hi);
}

// Triangle t's box, enlarged by its margin.
template <class S>
DEME_HD_INLINE void triangleBox(const S& s, const DetectionArgs& a, size_t t, double3& lo, double3& hi) {
    const double3* v = &s.cache.triVert[3 * t];
    const double e = marginOf(s, a, s.triangles.owner[t]);
    lo = make_double3(fmin(fmin(v[0].x, v[1].x), v[2].x) - e, fmin(fmin(v[0].y, v[1].y), v[2].y) - e,
                      fmin(fmin(v[0].z, v[1].z), v[2].z) - e);
    hi = make_double3(fmax(fmax(v[0].x, v[1].x), v[2].x) + e, fmax(fmax(v[0].y, v[1].y), v[2].y) + e,
                      fmax(fmax(v[0].z, v[1].z), v[2].z) + e);
}

// Which items a bin registry holds (the GPU's binning kernels take it as an argument).
enum BinnedKind : unsigned int { BINNED_SPHERES = 0u, BINNED_TRIANGLES = 1u };

// The bins triangle t's enlarged box covers (its box stored in a.triLo, a.triHi).
DEME_HD_INLINE BinBox triangleBinBox(const DetectionArgs& a, size_t t) { return binBox(a.grid, a.triLo[t], a.triHi[t]); }

// Whether bin (x, y, z), of index `bin`, holds the lower corner of the intersection of boxes starting
// at loA and lo. Outside a sheared cell by bin index, so that along a periodic axis the place in the
// period counts (a box cut to one period's bins, binBox, lists the corner's bin by it). In a sheared
// cell, x of a layer beyond a z face is a bin of the image layer (layerXBins), where the corner lies
// displaced by minus the offset times the layer's image; x is compared modulo the period.
DEME_HD_INLINE bool binOwnsPair(const BinGrid& g, const double3& loA, const double3& lo, int x, int y, int z,
                                uint64_t bin) {
    const double cx = fmax(loA.x, lo.x);
    if (!g.shear)
        return binIndex(g, binCoord(g, 0, cx), binCoord(g, 1, fmax(loA.y, lo.y)), binCoord(g, 2, fmax(loA.z, lo.z))) ==
               bin;
    if (binCoord(g, 1, fmax(loA.y, lo.y)) != y || binCoord(g, 2, fmax(loA.z, lo.z)) != z) return false;
    const int cxBin = binCoord(g, 0, cx - (double)layerImage(g, z) * g.shearOffset);
    return wrapBin(cxBin, g.nx) == wrapBin(x, g.nx);
}

// Whether analytical component j is a partner of a sphere at pA with enlarged radius eA.
template <class S>
DEME_HD_INLINE bool analyticalInReach(const S& s, const DetectionArgs& a, const uint8_t* maskRow, const double3& pA,
                                      double eA, unsigned int j) {
    const bodyID_t o = s.analytical.owner[j];
    if (!maskRow[s.owners.family[o]]) return false;
    const double dist = s.analytical.type[j] == ANAL_PLANE
                            ? planeSignedDistance(pA, s.cache.analPos[j], s.cache.analDir[j])
                            : cylinderSignedDistance(pA, s.cache.analPos[j], s.cache.analDir[j], s.analytical.radius[j],
                                                     s.analytical.inside[j] != 0);
    return dist < eA + marginOf(s, a, o);
}

// The first entry of a bin's entries [e0, e1) whose sphere id is above `sa` (e1 if none). A bin's
// entries are in ascending id order on both backends (spheres are registered in id order, and the
// GPU's sort by bin is stable), so a sphere skips at once the bins that hold no higher id -- all of
// them for the last sphere, however many bins a large one spans -- and the lower ids of the others.
DEME_HD_INLINE uint32_t firstEntryAbove(const BinsView& bins, uint32_t e0, uint32_t e1, bodyID_t sa) {
    if (e0 == e1 || bins.items[e1 - 1] <= sa) return e1;
    while (e0 < e1) {
        const uint32_t mid = (e0 + e1) >> 1;
        if (bins.items[mid] <= sa)
            e0 = mid + 1;
        else
            e1 = mid;
    }
    return e0;
}

// Sorts ids[0, n) ascending (a sphere's partner lists are short).
DEME_HD_INLINE void sortIds(bodyID_t* ids, unsigned int n) {
    for (unsigned int k = 1; k < n; k++) {
        const bodyID_t v = ids[k];
        unsigned int at = k;
        while (at > 0 && ids[at - 1] > v) {
            ids[at] = ids[at - 1];
            at--;
        }
        ids[at] = v;
    }
}

// A sphere that searches for its partners: what the search of any of its bins reads.
struct SearchedSphere {
    bodyID_t id, owner;
    double3 centre, lo, hi;  // its box, enlarged by its margin
    double reach;            // its enlarged radius
    // The bins its partners are looked for in: those of its box (as a registration by boxes
    // computes them, sphereBox), or by centre those of its centre's box grown by the largest reach
    // (which hold its box's bins, where its triangles are found by the lower-corner rule).
    BinBox bins;
    const uint8_t* maskRow;  // its family's row of the contact mask
};

template <class S>
DEME_HD_INLINE SearchedSphere searchedSphere(const S& s, const DetectionArgs& a, bodyID_t sa) {
    SearchedSphere A;
    A.id = sa;
    A.centre = sphereCentre(s, sa);
    A.owner = sphereOwner(s, sa);
    A.reach = (double)s.spheres.radius[sa] + marginOf(s, a, A.owner);
    boxAround(A.centre, A.reach, A.lo, A.hi);
    if (a.centreReach > 0.0) {
        const double h = A.reach + a.centreReach;  // a partner's centre is nearer than this
        A.bins = binBox(a.grid, make_double3(A.centre.x - h, A.centre.y - h, A.centre.z - h),
                        make_double3(A.centre.x + h, A.centre.y + h, A.centre.z + h));
    } else {
        A.bins = binBox(a.grid, A.lo, A.hi);
    }
    A.maskRow = a.familyMask + (size_t)s.owners.family[A.owner] * NUM_FAMILIES;
    return A;
}

// A's sphere partners that bin (x, y, z) reports: spheres b > A of another owner within reach, each
// pair from the one bin that holds the lower corner of the two boxes' intersection (by centre, from
// the one bin b is in); f(b) for each.
template <class S, class F>
DEME_HD_INLINE void spherePartnersInBin(const S& s, const DetectionArgs& a, const SearchedSphere& A, int x, int y,
                                        int z, F&& f) {
    const BinGrid& g = a.grid;
    const uint64_t bin = binIndex(g, x, y, z);
    const uint32_t e1 = a.sphereBins.end(bin);
    for (uint32_t e = firstEntryAbove(a.sphereBins, a.sphereBins.first(bin), e1, A.id); e < e1; e++) {
        // The geometric tests first: most entries fail them (spheres out of reach, or pairs another
        // bin reports), and they need only b's position and radius, read side by side; b's owner and
        // family are looked up for the rest.
        const bodyID_t b = a.sphereBins.items[e];
        // Across a periodic face: b's image nearest to A, in A's frame (the bins searched are A's
        // box's, unwrapped).
        const double3 pB = nearestImage(s.frame.periodic, A.centre, sphereCentre(s, b));
        const double rB = (double)s.spheres.radius[b];
        const bool shared = a.sharedExtraMargin >= 0.0;
        const bodyID_t oB0 = shared ? 0 : sphereOwner(s, b);
        const double eB = rB + (shared ? a.margin + a.sharedExtraMargin : marginOf(s, a, oB0));
        const double reach = A.reach + eB;
        const double3 d = A.centre - pB;
        if (fabs(d.x) > reach || fabs(d.y) > reach || fabs(d.z) > reach) continue;
        if (a.centreReach <= 0.0 && !binOwnsPair(g, A.lo, make_double3(pB.x - eB, pB.y - eB, pB.z - eB), x, y, z, bin))
            continue;
        if (dot(d, d) >= reach * reach) continue;
        const bodyID_t oB = shared ? sphereOwner(s, b) : oB0;
        if (oB == A.owner || !A.maskRow[s.owners.family[oB]]) continue;
        f(b);
    }
}

// A's triangle partners that bin (x, y, z) reports (the triangle's index t; each pair from one bin):
// f(t) for each. Without triangles (a.triangleBins.start null) none.
template <class S, class F>
DEME_HD_INLINE void trianglePartnersInBin(const S& s, const DetectionArgs& a, const SearchedSphere& A, int x, int y,
                                          int z, F&& f) {
    if (a.triangleBins.start == nullptr) return;
    const uint64_t bin = binIndex(a.grid, x, y, z);
    const uint32_t e1 = a.triangleBins.end(bin);
    for (uint32_t e = a.triangleBins.first(bin); e < e1; e++) {
        const uint32_t tri = a.triangleBins.items[e];
        const bodyID_t oT = s.triangles.owner[tri];
        if (!A.maskRow[s.owners.family[oT]]) continue;
        // The triangle's image nearest to A (across a periodic face), in A's frame.
        const double3* v0 = &s.cache.triVert[3 * (size_t)tri];
        const double3 shift = imageShift(s.frame.periodic, A.centre - v0[0]);
        const double3 lo = a.triLo[tri] + shift, hi = a.triHi[tri] + shift;
        if (lo.x > A.hi.x || lo.y > A.hi.y || lo.z > A.hi.z || hi.x < A.lo.x || hi.y < A.lo.y || hi.z < A.lo.z)
            continue;
        if (!binOwnsPair(a.grid, A.lo, lo, x, y, z, bin)) continue;
        double3 bary;
        const double3 c = closestPointOnTriangle(A.centre, v0[0] + shift, v0[1] + shift, v0[2] + shift, bary);
        if (length(A.centre - c) >= A.reach + marginOf(s, a, oT)) continue;
        f(tri);
    }
}

// A's analytical partners (every component is checked: they are few), by index j: f(j) for each.
template <class S, class F>
DEME_HD_INLINE void analyticalPartners(const S& s, const DetectionArgs& a, const SearchedSphere& A, F&& f) {
    const unsigned int nA = (unsigned int)(s.triangleIdBase() - s.analyticalIdBase());
    for (unsigned int j = 0; j < nA; j++)
        if (analyticalInReach(s, a, A.maskRow, A.centre, A.reach, j)) f(j);
}

// Sphere sa's partners (unified geometry ids) in contact-set order, into out[0, capacity); returns
// how many there are. If that is more than `capacity`, out holds no usable list: call again with
// room for all (capacity 0 counts only).
template <class S>
DEME_HD_INLINE unsigned int spherePartners(const S& s, const DetectionArgs& a, bodyID_t sa, bodyID_t* out,
                                           unsigned int capacity) {
    const SearchedSphere A = searchedSphere(s, a, sa);
    // 1. Sphere partners (each pair once, from its lower sphere).
    unsigned int nSph = 0;
    forEachBinOf(a.grid, A.bins, [&](int x, int y, int z) {
        spherePartnersInBin(s, a, A, x, y, z, [&](bodyID_t b) {
            if (nSph < capacity) out[nSph] = b;
            nSph++;
        });
    });
    // 2. Triangle partners, kept behind the spheres for now.
    unsigned int nTri = 0;
    const bodyID_t triBase = s.triangleIdBase();
    if (a.triangleBins.start != nullptr) {
        forEachBinOf(a.grid, A.bins, [&](int x, int y, int z) {
            trianglePartnersInBin(s, a, A, x, y, z, [&](uint32_t tri) {
                if (nSph + nTri < capacity) out[nSph + nTri] = triBase + tri;
                nTri++;
            });
        });
    }
    // 3. Analytical components.
    unsigned int nAna = 0;
    analyticalPartners(s, a, A, [&](unsigned int) { nAna++; });
    const unsigned int total = nSph + nAna + nTri;
    if (total > capacity) return total;
    // 4. In order: [spheres by id | analytical by id | triangles by id] (the unified ids' order).
    sortIds(out, nSph);
    sortIds(out + nSph, nTri);
    for (unsigned int k = nTri; k > 0; k--) out[nSph + nAna + k - 1] = out[nSph + k - 1];
    unsigned int at = nSph;
    analyticalPartners(s, a, A, [&](unsigned int j) { out[at++] = s.analyticalIdBase() + j; });
    return total;
}

// Rows first, first + step, ... of sphere A's box (forEachBinOfRows): its sphere and triangle
// partners those bins report and, for first = 0, its analytical ones; f(unified id) for each, in no
// particular order. The `step` threads of the GPU's lab-scale search split a sphere so, and its
// partners are then put in contact-set order (ascending unified id) at once.
template <class S, class F>
DEME_HD_INLINE void spherePartnersInRows(const S& s, const DetectionArgs& a, const SearchedSphere& A,
                                         unsigned int first, unsigned int step, F&& f) {
    const bodyID_t triBase = s.triangleIdBase();
    forEachBinOfRows(a.grid, A.bins, first, step, [&](int x, int y, int z) {
        spherePartnersInBin(s, a, A, x, y, z, f);
        trianglePartnersInBin(s, a, A, x, y, z, [&](uint32_t tri) { f(triBase + tri); });
    });
    if (first == 0) analyticalPartners(s, a, A, [&](unsigned int j) { f(s.analyticalIdBase() + j); });
}

}  // namespace deme
