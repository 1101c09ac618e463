// Contact detection on the GPU (the kinematics side): the per-item rules of
// kinematics/DetectionRules.h, one thread per item; items are sorted into bins with CUB
// (DeviceKinematics). Compiled at run time by NVRTC. With dormant spheres (the active box,
// kinematics/DormantRules.h) the moving spheres are listed once (`ids`, ascending) and only they are
// binned and searched; a null `ids` means every sphere.
#include "kinematics/BinSlabs.h"
#include "kinematics/DetectionRules.h"
#include "kinematics/DormantRules.h"
#include "state/StateView.h"

#include "backend/cuda/kernels/PairAKernels.cuh"

namespace deme {

namespace {

__device__ inline size_t globalIndex() { return (size_t)blockIdx.x * blockDim.x + threadIdx.x; }

}  // namespace

// Triangle t's enlarged box (its bins follow from it: triangleBinBox).
extern "C" __global__ void deme_triangle_boxes(StateView s, DetectionArgs a, double3* triLo, double3* triHi) {
    const size_t t = globalIndex();
    if (t >= s.numTriangles) return;
    triangleBox(s, a, t, triLo[t], triHi[t]);
}

// The bins item i of a kind covers: spheres' from their boxes, computed (not stored: 24 bytes per
// sphere), triangles' from the boxes deme_triangle_boxes stored in a.triLo, a.triHi.
__device__ inline BinBox binnedBox(const StateView& s, const DetectionArgs& a, unsigned int kind, size_t i) {
    return kind == BINNED_SPHERES ? sphereBinBox(s, a, i) : triangleBinBox(a, i);
}

// The bins' item lists by a counting sort, with no per-entry keys (docs/memory.md): `start` has
// numBins + 2 entries, zeroed. 1. deme_bin_count: every item ids[k] adds one at start[bin + 1] for
// each bin of its box. 2. An exclusive sum over all numBins + 2: start[bin + 1] is then bin's first
// entry and start[numBins + 1] the number of entries. 3. deme_bin_scatter: each item takes a slot in
// each of its bins by an atomic add on start[bin + 1], which ends at the bin's end, the next bin's
// first entry: start[0, numBins] are then every bin's first entry and the end. 4. deme_bin_sort:
// each bin's items in increasing id (the scatter's order is the atomics'), as the searches expect.
// `lanes` threads share an item (thread t: item t / lanes, its box's rows t % lanes, + lanes, ...):
// at lab scale one thread walking a large sphere's hundreds of bins was a detection's critical path
// (docs/cuda-backend.md, "Detection at lab scale"); 1 is a thread per item.
// A detection in slabs (kinematics/BinSlabs.h) bins the layers `layers` only: each item's box cut to
// them, `start` indexed from their first bin.
extern "C" __global__ void deme_bin_count(StateView s, DetectionArgs a, unsigned int kind, const bodyID_t* ids,
                                          unsigned int n, unsigned int lanes, LayerRange layers, unsigned int* start) {
    const size_t t = globalIndex(), k = t / lanes;
    if (k >= n) return;
    const BinGrid& g = a.grid;
    BinBox box = binnedBox(s, a, kind, ids ? (size_t)ids[k] : k);
    if (!clipToLayers(g, box, layers)) return;
    const uint64_t first = firstBinOfLayer(g, layers.from);  // 0 for the whole grid
    forEachBinOfRows(g, box, (unsigned int)(t % lanes), lanes,
                     [&](int x, int y, int z) { atomicAdd(&start[binIndex(g, x, y, z) - first + 1], 1u); });
}

extern "C" __global__ void deme_bin_scatter(StateView s, DetectionArgs a, unsigned int kind, const bodyID_t* ids,
                                            unsigned int n, unsigned int lanes, LayerRange layers, unsigned int* start,
                                            unsigned int* items) {
    const size_t t = globalIndex(), k = t / lanes;
    if (k >= n) return;
    const BinGrid& g = a.grid;
    const size_t i = ids ? (size_t)ids[k] : k;
    BinBox box = binnedBox(s, a, kind, i);
    if (!clipToLayers(g, box, layers)) return;
    const uint64_t first = firstBinOfLayer(g, layers.from);  // 0 for the whole grid
    forEachBinOfRows(g, box, (unsigned int)(t % lanes), lanes, [&](int x, int y, int z) {
        items[atomicAdd(&start[binIndex(g, x, y, z) - first + 1], 1u)] = (unsigned int)i;
    });
}

// One thread per bin: an insertion sort (bins hold a few items; the grid's sizing rule keeps them so).
extern "C" __global__ void deme_bin_sort(const unsigned int* start, unsigned long long numBins, unsigned int* items) {
    const size_t bin = globalIndex();
    if (bin >= numBins) return;
    const unsigned int first = start[bin], end = start[bin + 1];
    for (unsigned int e = first + 1; e < end; e++) {
        const unsigned int item = items[e];
        unsigned int at = e;
        for (; at > first && items[at - 1] > item; at--) items[at] = items[at - 1];
        items[at] = item;
    }
}

// count[key]++ for every (bin, item) entry. The exclusive sum of count[0, numBins] is then the first
// entry of each bin in bin-sorted order (and count[numBins], left 0, gives the total). One thread per
// entry: a bin's start must not be found by walking the gaps between occupied bins, because a grid
// that grains fill only in part (a mixer's grains sit in one third of its box) leaves gaps of
// millions of bins, and one thread writing those serially took most of a detection.
extern "C" __global__ void deme_bin_counts(const unsigned int* keys, unsigned int n, unsigned int* count) {
    const size_t i = globalIndex();
    if (i >= n) return;
    atomicAdd(&count[keys[i]], 1u);
}

// Per searched sphere A = ids[k]: its partners, then (with a dormant registry, d.start not null)
// its dormant partners as (lower, higher) pairs, which deme_pairs_from_keys puts in order after a
// sort. With `outB` null, counts them into count[k]; otherwise writes them from offset[k] to
// offset[k + 1] (the exclusive sum of the counts, which may have been taken in place), and A into
// `outA` where given (without dormant partners every A is sphere k, implied by the offsets). Spheres of
// radius `wideRadius` or more are left to deme_pair_search_wide (count[k] stays 0 here). A
// detection in slabs searches the spheres whose centres' bins lie in the layers `searched` only
// (the others' counts stay as they are: another slab's).
extern "C" __global__ void deme_pair_search(StateView s, DetectionArgs a, DormantBinsView d, const bodyID_t* ids,
                                            unsigned int n, float wideRadius, LayerRange searched, PairOffset* count,
                                            const PairOffset* offset, bodyID_t* outA, bodyID_t* outB) {
    const size_t k = globalIndex();
    if (k >= n) return;
    const bodyID_t sa = ids ? ids[k] : (bodyID_t)k;
    if (s.spheres.radius[sa] >= wideRadius) return;
    if (!isWholeGrid(a.grid, searched) && !searched.holds(pointBin(a.grid, sphereCentre(s, sa)).lo[2])) return;
    if (outB == nullptr) {
        count[k] = spherePartners(s, a, sa, nullptr, 0u) + (d.start ? dormantPartners(s, a, d, sa, nullptr, 0u) : 0u);
        return;
    }
    const PairOffset base = offset[k];
    const unsigned int found = (unsigned int)(offset[k + 1] - base);
    const unsigned int own = spherePartners(s, a, sa, outB + base, found);
    if (outA)  // null: the offsets imply A (CudaKinematics, kernels/PairAKernels.cuh)
        for (unsigned int j = 0; j < own; j++) outA[base + j] = sa;
    if (!d.start) return;
    bodyID_t* more = outB + base + own;
    const unsigned int nd = dormantPartners(s, a, d, sa, more, found - own);
    for (unsigned int j = 0; j < nd; j++) {
        const bodyID_t b = more[j];
        outA[base + own + j] = sa < b ? sa : b;
        outB[base + own + j] = sa < b ? b : sa;
    }
}

// --- Lab scale (backend/cuda/DetectionLanes.h; docs/cuda-backend.md, "Detection at lab scale"):
// there a detection's time is the longest chain of dependent loads one thread walks, so a sphere's
// search is split among `lanes` threads, each taking every lanes-th row of bins of its box
// (forEachBinOfRows), and the few wide spheres (radius `wideRadius` or more: a ball among grains,
// whose box spans hundreds of bins) are searched by a warp each. Never with a dormant registry.

// Sphere sa's (the k-th searched) share of thread `lane` of `lanes`: counting (outB null), its
// partners added to count[k] (zeroed); filling, each written from offset[k] on at a slot taken by
// an atomic add on *cursor (zeroed), in no order (the sphere's partners are ordered afterwards).
__device__ inline void searchLane(const StateView& s, const DetectionArgs& a, bodyID_t sa, size_t k, unsigned int lane,
                                  unsigned int lanes, PairOffset* count, const PairOffset* offset, unsigned int* cursor,
                                  bodyID_t* outB) {
    const SearchedSphere A = searchedSphere(s, a, sa);
    if (outB == nullptr) {
        unsigned int found = 0;
        spherePartnersInRows(s, a, A, lane, lanes, [&](bodyID_t) { found++; });
        if (found) atomicAdd(&count[k], (PairOffset)found);
        return;
    }
    const PairOffset base = offset[k];
    spherePartnersInRows(s, a, A, lane, lanes, [&](bodyID_t b) { outB[base + atomicAdd(cursor, 1u)] = b; });
}

// Every sphere but the wide ones, `lanes` threads each (thread t: sphere t / lanes; cursor[k] is
// sphere k's). Its registers are capped so that four blocks of 256 share a multiprocessor: uncapped
// (132 registers) one block did, and a grid of several threads a sphere took as many waves.
extern "C" __global__ void __launch_bounds__(256, 4)
    deme_pair_search_lanes(StateView s, DetectionArgs a, unsigned int n, unsigned int lanes, float wideRadius,
                           PairOffset* count, const PairOffset* offset, unsigned int* cursor, bodyID_t* outB) {
    const size_t t = globalIndex(), k = t / lanes;
    if (k >= n || s.spheres.radius[k] >= wideRadius) return;
    searchLane(s, a, (bodyID_t)k, k, (unsigned int)(t % lanes), lanes, count, offset, cursor ? &cursor[k] : nullptr,
               outB);
}

// After deme_pair_search_lanes: each sphere's partners, outB[offset[k], offset[k + 1]), in
// contact-set order (ascending unified id: spheres, analytical components, triangles), and A (a
// pair's type follows from B: state/ContactTypeOf.h). Not the wide spheres (deme_pair_rank_wide,
// deme_pair_finish_wide).
extern "C" __global__ void deme_pair_order(StateView s, unsigned int n, float wideRadius, const PairOffset* offset,
                                           bodyID_t* outA, bodyID_t* outB) {
    const size_t k = globalIndex();
    if (k >= n || s.spheres.radius[k] >= wideRadius) return;
    const PairOffset first = offset[k], last = offset[k + 1];
    sortIds(outB + first, (unsigned int)(last - first));
    for (PairOffset j = first; j < last; j++) outA[j] = (bodyID_t)k;
}

// The wide spheres wide[0, nWide), `lanes` threads each (thread t: sphere wide[t / lanes]; cursor[w]
// is the w-th's).
extern "C" __global__ void deme_pair_search_wide(StateView s, DetectionArgs a, const bodyID_t* wide, unsigned int nWide,
                                                 unsigned int lanes, PairOffset* count, const PairOffset* offset,
                                                 unsigned int* cursor, bodyID_t* outB) {
    const size_t t = globalIndex(), w = t / lanes;
    if (w >= nWide) return;
    searchLane(s, a, wide[w], wide[w], (unsigned int)(t % lanes), lanes, count, offset, cursor ? &cursor[w] : nullptr,
               outB);
}

// Each wide sphere's partners, outB[offset[k], offset[k + 1]), in contact-set order (ascending
// unified id: spheres, analytical components, triangles) into outA's same range: each element goes
// to its rank (the ids are distinct), the range's elements shared among the sphere's lanes.
extern "C" __global__ void deme_pair_rank_wide(const bodyID_t* wide, unsigned int nWide, unsigned int lanes,
                                               const PairOffset* offset, bodyID_t* outA, const bodyID_t* outB) {
    const size_t t = globalIndex(), w = t / lanes;
    if (w >= nWide) return;
    const bodyID_t k = wide[w];
    const PairOffset first = offset[k], last = offset[k + 1];
    for (PairOffset e = first + t % lanes; e < last; e += lanes) {
        const bodyID_t id = outB[e];
        PairOffset rank = 0;
        for (PairOffset j = first; j < last; j++) rank += outB[j] < id ? 1u : 0u;
        outA[first + rank] = id;
    }
}

// Then the ordered ids back into outB, and A into outA.
extern "C" __global__ void deme_pair_finish_wide(const bodyID_t* wide, unsigned int nWide, unsigned int lanes,
                                                 const PairOffset* offset, bodyID_t* outA, bodyID_t* outB) {
    const size_t t = globalIndex(), w = t / lanes;
    if (w >= nWide) return;
    const bodyID_t k = wide[w];
    for (PairOffset e = offset[k] + t % lanes; e < offset[k + 1]; e += lanes) {
        outB[e] = outA[e];
        outA[e] = k;
    }
}

// --- The dormant registry, rebuilt only when the owners' families differ from those it was built for.

// flags[0] = 1 if an owner's family is not the one the registry was built for; flags[1] = 1 if an
// owner that can move (movable[o], walls and meshes) reaches a dormant family (no registry then).
extern "C" __global__ void deme_dormant_check(StateView s, const family_t* builtFor, const uint8_t* movable,
                                              const uint8_t* dormant, const uint8_t* familyMask, unsigned int* flags) {
    const size_t o = globalIndex();
    if (o >= s.numOwners) return;
    const family_t f = s.owners.family[o];
    if (f != builtFor[o]) flags[0] = 1u;  // every writer writes 1
    if (movable[o] && movingFamilyReachesDormant(dormant, familyMask, f)) flags[1] = 1u;
}

// Per sphere: 1 in isMoving or isDormant, and a dormant sphere's reach (0 for a moving one), whose
// largest value widens every search.
extern "C" __global__ void deme_dormant_flags(StateView s, const uint8_t* dormant, const float* familyExtraMargin,
                                              unsigned int* isMoving, unsigned int* isDormant, double* reach) {
    const size_t i = globalIndex();
    if (i >= s.numSpheres) return;
    const bool d = sphereIsDormant(s, dormant, i);
    isMoving[i] = d ? 0u : 1u;
    isDormant[i] = d ? 1u : 0u;
    reach[i] = d ? dormantReachOf(s, familyExtraMargin, i) : 0.0;
}

// The moving spheres at their offsets (ascending), the dormant ones as (centre bin, sphere) entries at
// theirs (in sphere order: a stable sort by bin keeps each bin's spheres ascending).
extern "C" __global__ void deme_dormant_scatter(StateView s, BinGrid g, const uint8_t* dormant,
                                                const unsigned int* movingOffset, const unsigned int* dormantOffset,
                                                bodyID_t* moving, unsigned int* keys, unsigned int* items) {
    const size_t i = globalIndex();
    if (i >= s.numSpheres) return;
    if (!sphereIsDormant(s, dormant, i)) {
        moving[movingOffset[i]] = (bodyID_t)i;
        return;
    }
    keys[dormantOffset[i]] = dormantBinOf(s, g, i);
    items[dormantOffset[i]] = (unsigned int)i;
}

// --- Pairs found from both sides (moving and dormant partners) into (A, B) order.

// keys[i] = (A << bBits) | B, idx[i] = i (the sort's values). B takes bBits bits (any geometry id),
// A the sphere ids' bits above them: the sort runs over those bits only (fewer radix passes than
// over two whole 32-bit halves).
extern "C" __global__ void deme_pair_keys(const bodyID_t* geomA, const bodyID_t* geomB, unsigned int n, int bBits,
                                          unsigned long long* keys, unsigned int* idx) {
    const size_t i = globalIndex();
    if (i >= n) return;
    keys[i] = ((unsigned long long)geomA[i] << bBits) | (unsigned long long)geomB[i];
    idx[i] = (unsigned int)i;
}

// The sorted keys back into pairs.
extern "C" __global__ void deme_pairs_from_keys(const unsigned long long* keys, unsigned int n, int bBits,
                                                bodyID_t* geomA, bodyID_t* geomB) {
    const size_t i = globalIndex();
    if (i >= n) return;
    geomA[i] = (bodyID_t)(keys[i] >> bBits);
    geomB[i] = (bodyID_t)(keys[i] & ((1ull << bBits) - 1ull));
}

}  // namespace deme
