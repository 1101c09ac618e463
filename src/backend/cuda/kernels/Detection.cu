// Contact detection on the GPU (the kinematics side), the same method as the CPU detector
// (kinematics/ContactDetection.h): every geometry, enlarged by its margin, is registered in each bin
// its box touches; each sphere A then searches its bins, and a pair is reported only from the bin
// holding the lower corner of the two boxes' intersection, so exactly once. Output per sphere is in
// the CPU's order (sphere partners by id, analytical components, triangles by id), so the set is
// sorted by (A, B) and contact history maps by binary search. Compiled at run time by NVRTC.
#include "backend/cuda/kernels/KernelArgs.cuh"
#include "physics/ContactGeometry.h"
#include "runtime/StateView.h"

namespace deme {

namespace {

__device__ inline size_t globalIndex() { return (size_t)blockIdx.x * blockDim.x + threadIdx.x; }

__device__ inline int binCoord(double x, double origin, double size, int n) {
    const double f = floor((x - origin) / size);
    if (!(f > 0.0)) return 0;  // also NaN; the integrator reports NaN positions
    if (f >= (double)(n - 1)) return n - 1;
    return (int)f;
}

__device__ inline unsigned int binIndex(const BinGridView& g, int x, int y, int z) {
    return (unsigned int)x + (unsigned int)g.nx * ((unsigned int)y + (unsigned int)g.ny * (unsigned int)z);
}

__device__ inline void setBinBox(const BinGridView& g, size_t i, const double3& lo, const double3& hi, int* binLo,
                                 int* binHi, unsigned int* count) {
    const int lx = binCoord(lo.x, g.origin.x, g.size, g.nx), ly = binCoord(lo.y, g.origin.y, g.size, g.ny),
              lz = binCoord(lo.z, g.origin.z, g.size, g.nz);
    const int hx = binCoord(hi.x, g.origin.x, g.size, g.nx), hy = binCoord(hi.y, g.origin.y, g.size, g.ny),
              hz = binCoord(hi.z, g.origin.z, g.size, g.nz);
    binLo[3 * i] = lx;
    binLo[3 * i + 1] = ly;
    binLo[3 * i + 2] = lz;
    binHi[3 * i] = hx;
    binHi[3 * i + 1] = hy;
    binHi[3 * i + 2] = hz;
    count[i] = (unsigned int)((hx - lx + 1) * (hy - ly + 1) * (hz - lz + 1));
}

__device__ inline double marginOf(const StateView& s, const float* familyExtraMargin, double margin, bodyID_t owner) {
    return margin + (double)familyExtraMargin[s.owners.family[owner]];
}

// Sorts ids[0, n) ascending (per-sphere partner lists are short).
__device__ inline void insertionSort(bodyID_t* ids, unsigned int n) {
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

// Whether analytical component j is a partner of a sphere at pA with enlarged radius eA.
__device__ inline bool analyticalInReach(const StateView& s, const PairSearchArgs& a, const uint8_t* maskRow,
                                         const double3& pA, double eA, unsigned int j) {
    const bodyID_t oJ = s.analytical.owner[j];
    if (!maskRow[s.owners.family[oJ]]) return false;
    const double dist = s.analytical.type[j] == ANAL_PLANE
                            ? planeSignedDistance(pA, s.cache.analPos[j], s.cache.analDir[j])
                            : cylinderSignedDistance(pA, s.cache.analPos[j], s.cache.analDir[j], s.analytical.radius[j],
                                                     s.analytical.inside[j] != 0);
    return dist < eA + marginOf(s, a.familyExtraMargin, a.margin, oJ);
}

}  // namespace

extern "C" __global__ void deme_sphere_bin_boxes(StateView s, BinGridView g, double margin,
                                                 const float* familyExtraMargin, int* binLo, int* binHi,
                                                 unsigned int* count) {
    const size_t i = globalIndex();
    if (i >= s.numSpheres) return;
    const double e = (double)s.spheres.radius[i] + marginOf(s, familyExtraMargin, margin, s.spheres.owner[i]);
    const double3 p = s.cache.spherePos[i];
    setBinBox(g, i, make_double3(p.x - e, p.y - e, p.z - e), make_double3(p.x + e, p.y + e, p.z + e), binLo, binHi,
              count);
}

extern "C" __global__ void deme_triangle_bin_boxes(StateView s, BinGridView g, double margin,
                                                   const float* familyExtraMargin, double3* triLo, double3* triHi,
                                                   int* binLo, int* binHi, unsigned int* count) {
    const size_t t = globalIndex();
    if (t >= s.numTriangles) return;
    const double3* v = s.cache.triVert + 3 * t;
    const double em = marginOf(s, familyExtraMargin, margin, s.triangles.owner[t]);
    const double3 lo = make_double3(fmin(fmin(v[0].x, v[1].x), v[2].x) - em, fmin(fmin(v[0].y, v[1].y), v[2].y) - em,
                                    fmin(fmin(v[0].z, v[1].z), v[2].z) - em);
    const double3 hi = make_double3(fmax(fmax(v[0].x, v[1].x), v[2].x) + em, fmax(fmax(v[0].y, v[1].y), v[2].y) + em,
                                    fmax(fmax(v[0].z, v[1].z), v[2].z) + em);
    triLo[t] = lo;
    triHi[t] = hi;
    setBinBox(g, t, lo, hi, binLo, binHi, count);
}

// (bin, item) entries of every item in every bin of its box, at the item's offset (in item order,
// so a stable sort by bin keeps each bin's items ascending).
extern "C" __global__ void deme_bin_entries(BinGridView g, unsigned int n, const int* binLo, const int* binHi,
                                            const unsigned int* offset, unsigned int* keys, unsigned int* items) {
    const size_t i = globalIndex();
    if (i >= n) return;
    unsigned int at = offset[i];
    for (int z = binLo[3 * i + 2]; z <= binHi[3 * i + 2]; z++)
        for (int y = binLo[3 * i + 1]; y <= binHi[3 * i + 1]; y++)
            for (int x = binLo[3 * i]; x <= binHi[3 * i]; x++) {
                keys[at] = binIndex(g, x, y, z);
                items[at] = (unsigned int)i;
                at++;
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

// Per sphere A: its partners. With `outB` null, counts them into count[A]; otherwise writes them
// from offset[A] on.
extern "C" __global__ void deme_pair_search(StateView s, PairSearchArgs a, unsigned int* count,
                                            const unsigned int* offset, bodyID_t* outA, bodyID_t* outB,
                                            uint8_t* outType) {
    const size_t ia = globalIndex();
    if (ia >= s.numSpheres) return;
    const bodyID_t sa = (bodyID_t)ia;
    const BinGridView& g = a.grid;
    const double3 pA = s.cache.spherePos[sa];
    const bodyID_t oA = s.spheres.owner[sa];
    const double eA = (double)s.spheres.radius[sa] + marginOf(s, a.familyExtraMargin, a.margin, oA);
    const double3 loA = make_double3(pA.x - eA, pA.y - eA, pA.z - eA);
    const uint8_t* maskRow = a.familyMask + (size_t)s.owners.family[oA] * NUM_FAMILIES;
    const bool write = outB != nullptr;
    const unsigned int base = write ? offset[sa] : 0u;
    unsigned int nSph = 0;
    // Sphere partners, then triangle partners after them (moved behind the analytical ones below).
    for (int z = a.sphereBinLo[3 * sa + 2]; z <= a.sphereBinHi[3 * sa + 2]; z++)
        for (int y = a.sphereBinLo[3 * sa + 1]; y <= a.sphereBinHi[3 * sa + 1]; y++)
            for (int x = a.sphereBinLo[3 * sa]; x <= a.sphereBinHi[3 * sa]; x++) {
                const unsigned int bin = binIndex(g, x, y, z);
                for (unsigned int e = a.sphereBinStart[bin]; e < a.sphereBinStart[bin + 1]; e++) {
                    const bodyID_t b = a.sphereBinItems[e];
                    if (b <= sa) continue;
                    const bodyID_t oB = s.spheres.owner[b];
                    if (oB == oA || !maskRow[s.owners.family[oB]]) continue;
                    const double3 pB = s.cache.spherePos[b];
                    const double eB = (double)s.spheres.radius[b] + marginOf(s, a.familyExtraMargin, a.margin, oB);
                    const double reach = eA + eB;
                    const double3 d = pA - pB;
                    if (fabs(d.x) > reach || fabs(d.y) > reach || fabs(d.z) > reach) continue;
                    if (binCoord(fmax(loA.x, pB.x - eB), g.origin.x, g.size, g.nx) != x ||
                        binCoord(fmax(loA.y, pB.y - eB), g.origin.y, g.size, g.ny) != y ||
                        binCoord(fmax(loA.z, pB.z - eB), g.origin.z, g.size, g.nz) != z)
                        continue;
                    if (dot(d, d) >= reach * reach) continue;
                    if (write) outB[base + nSph] = b;
                    nSph++;
                }
            }
    unsigned int nTri = 0;
    const bodyID_t triBase = s.triangleIdBase();
    if (s.numTriangles > 0) {
        for (int z = a.sphereBinLo[3 * sa + 2]; z <= a.sphereBinHi[3 * sa + 2]; z++)
            for (int y = a.sphereBinLo[3 * sa + 1]; y <= a.sphereBinHi[3 * sa + 1]; y++)
                for (int x = a.sphereBinLo[3 * sa]; x <= a.sphereBinHi[3 * sa]; x++) {
                    const unsigned int bin = binIndex(g, x, y, z);
                    for (unsigned int e = a.triBinStart[bin]; e < a.triBinStart[bin + 1]; e++) {
                        const unsigned int tri = a.triBinItems[e];
                        const bodyID_t oT = s.triangles.owner[tri];
                        if (!maskRow[s.owners.family[oT]]) continue;
                        const double3 lo = a.triLo[tri], hi = a.triHi[tri];
                        if (lo.x > pA.x + eA || lo.y > pA.y + eA || lo.z > pA.z + eA || hi.x < loA.x || hi.y < loA.y ||
                            hi.z < loA.z)
                            continue;
                        if (binCoord(fmax(loA.x, lo.x), g.origin.x, g.size, g.nx) != x ||
                            binCoord(fmax(loA.y, lo.y), g.origin.y, g.size, g.ny) != y ||
                            binCoord(fmax(loA.z, lo.z), g.origin.z, g.size, g.nz) != z)
                            continue;
                        const double3* v = s.cache.triVert + 3 * (size_t)tri;
                        double3 bary;
                        const double3 c = closestPointOnTriangle(pA, v[0], v[1], v[2], bary);
                        if (length(pA - c) >= eA + marginOf(s, a.familyExtraMargin, a.margin, oT)) continue;
                        // Kept behind this sphere's slots for now; placed after the analytical ones below.
                        if (write) outB[base + nSph + nTri] = triBase + tri;
                        nTri++;
                    }
                }
    }
    unsigned int nAna = 0;
    for (unsigned int j = 0; j < s.numAnalytical; j++) {
        if (!analyticalInReach(s, a, maskRow, pA, eA, j)) continue;
        nAna++;
    }
    if (!write) {
        count[sa] = nSph + nTri + nAna;
        return;
    }
    bodyID_t* mine = outB + base;
    insertionSort(mine, nSph);
    insertionSort(mine + nSph, nTri);
    // Move the triangles behind the analytical components: [spheres | analytical | triangles].
    for (unsigned int k = nTri; k > 0; k--) mine[nSph + nAna + k - 1] = mine[nSph + k - 1];
    unsigned int at = nSph;
    for (unsigned int j = 0; j < s.numAnalytical; j++) {
        if (!analyticalInReach(s, a, maskRow, pA, eA, j)) continue;
        mine[at++] = s.analyticalIdBase() + j;
    }
    const unsigned int total = nSph + nAna + nTri;
    for (unsigned int k = 0; k < total; k++) {
        outA[base + k] = sa;
        outType[base + k] = k < nSph ? SPHERE_SPHERE : k < nSph + nAna ? SPHERE_ANALYTICAL : SPHERE_TRIANGLE;
    }
}

// Contact history across a re-detection: a pair found again keeps its wildcards and mesh state,
// a new pair starts from zero. The old set is sorted by (A, B).
extern "C" __global__ void deme_map_history(const bodyID_t* newA, const bodyID_t* newB, unsigned int nNew,
                                            const bodyID_t* oldA, const bodyID_t* oldB, unsigned int nOld,
                                            const float* oldWildcards, const uint8_t* oldMeshState, unsigned int W,
                                            float* newWildcards, uint8_t* newMeshState) {
    const size_t i = globalIndex();
    if (i >= nNew) return;
    const unsigned long long key = ((unsigned long long)newA[i] << 32) | newB[i];
    unsigned int lo = 0, hi = nOld;
    while (lo < hi) {
        const unsigned int mid = (lo + hi) >> 1;
        const unsigned long long k = ((unsigned long long)oldA[mid] << 32) | oldB[mid];
        if (k < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    const bool found = lo < nOld && (((unsigned long long)oldA[lo] << 32) | oldB[lo]) == key;
    for (unsigned int w = 0; w < W; w++) newWildcards[i * W + w] = found ? oldWildcards[(size_t)lo * W + w] : 0.f;
    newMeshState[i] = found ? oldMeshState[lo] : (uint8_t)0;
}

}  // namespace deme
