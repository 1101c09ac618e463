// Contact detection on the GPU (the kinematics side): the per-item rules of
// kinematics/DetectionRules.h, one thread per item; items are sorted into bins with CUB
// (DeviceKinematics). Compiled at run time by NVRTC.
#include "kinematics/DetectionRules.h"
#include "state/StateView.h"

namespace deme {

namespace {

__device__ inline size_t globalIndex() { return (size_t)blockIdx.x * blockDim.x + threadIdx.x; }

}  // namespace

extern "C" __global__ void deme_sphere_bin_boxes(StateView s, DetectionArgs a, int* binLo, int* binHi,
                                                 unsigned int* count) {
    const size_t i = globalIndex();
    if (i >= s.numSpheres) return;
    double3 lo, hi;
    sphereBox(s, a, i, lo, hi);
    const BinBox b = binBox(a.grid, lo, hi);
    storeBinBox(b, i, binLo, binHi);
    count[i] = b.count();
}

extern "C" __global__ void deme_triangle_bin_boxes(StateView s, DetectionArgs a, double3* triLo, double3* triHi,
                                                   int* binLo, int* binHi, unsigned int* count) {
    const size_t t = globalIndex();
    if (t >= s.numTriangles) return;
    triangleBox(s, a, t, triLo[t], triHi[t]);
    const BinBox b = binBox(a.grid, triLo[t], triHi[t]);
    storeBinBox(b, t, binLo, binHi);
    count[t] = b.count();
}

// (bin, item) entries of every item in every bin of its box, at the item's offset (in item order,
// so a stable sort by bin keeps each bin's items ascending).
extern "C" __global__ void deme_bin_entries(BinGrid g, unsigned int n, const int* binLo, const int* binHi,
                                            const unsigned int* offset, unsigned int* keys, unsigned int* items) {
    const size_t i = globalIndex();
    if (i >= n) return;
    unsigned int at = offset[i];
    for (int z = binLo[3 * i + 2]; z <= binHi[3 * i + 2]; z++)
        for (int y = binLo[3 * i + 1]; y <= binHi[3 * i + 1]; y++)
            for (int x = binLo[3 * i]; x <= binHi[3 * i]; x++) {
                keys[at] = (unsigned int)binIndex(g, x, y, z);
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

// Per sphere A: its partners. With `outB` null, counts them into count[A]; otherwise writes the
// count[A] of them from offset[A] on.
extern "C" __global__ void deme_pair_search(StateView s, DetectionArgs a, unsigned int* count,
                                            const unsigned int* offset, bodyID_t* outA, bodyID_t* outB,
                                            uint8_t* outType) {
    const size_t ia = globalIndex();
    if (ia >= s.numSpheres) return;
    const bodyID_t sa = (bodyID_t)ia;
    if (outB == nullptr) {
        count[sa] = spherePartners(s, a, sa, nullptr, 0u);
        return;
    }
    const unsigned int base = offset[sa];
    const unsigned int n = spherePartners(s, a, sa, outB + base, count[sa]);
    for (unsigned int k = 0; k < n; k++) {
        outA[base + k] = sa;
        outType[base + k] = contactTypeOf(s, outB[base + k]);
    }
}

}  // namespace deme
