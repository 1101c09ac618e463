// The uniform bin grid of contact detection (paper §2.1) and the per-item arithmetic on it, for the
// CPU's loops and the GPU's kernels alike (NVRTC compiles this header).
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

struct BinGrid {
    double3 origin;
    double size;
    int nx, ny, nz;
    DEME_HD uint64_t numBins() const { return (uint64_t)nx * (uint64_t)ny * (uint64_t)nz; }
};

// The bin coordinate of x along an axis of n bins, clamped to the grid: geometries beyond the domain
// (a mesh that reaches out of it) register in the border bins.
DEME_HD inline int binCoord(double x, double origin, double size, int n) {
    const double f = floor((x - origin) / size);
    if (!(f > 0.0)) return 0;  // also maps NaN to 0; NaN positions are caught by the integrator
    if (f >= (double)(n - 1)) return n - 1;
    return (int)f;
}

// 64-bit on the host; 32-bit in GPU code, where 64-bit multiplies are several instructions in the
// pair search's inner loops and exact anyway: the CUDA backend refuses grids of 2^32 bins or more
// (its bin keys are 32-bit).
DEME_HD inline uint64_t binIndex(const BinGrid& g, int x, int y, int z) {
#if defined(__CUDACC_RTC__)
    return (uint32_t)x + (uint32_t)g.nx * ((uint32_t)y + (uint32_t)g.ny * (uint32_t)z);
#else
    return (uint64_t)x + (uint64_t)g.nx * ((uint64_t)y + (uint64_t)g.ny * (uint64_t)z);
#endif
}

// The bins a box [lo, hi] touches: lo[a]..hi[a] along each axis a.
struct BinBox {
    int lo[3], hi[3];
    DEME_HD unsigned int count() const {
        return (unsigned int)((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1));
    }
};

DEME_HD inline BinBox binBox(const BinGrid& g, const double3& lo, const double3& hi) {
    BinBox b;
    b.lo[0] = binCoord(lo.x, g.origin.x, g.size, g.nx);
    b.lo[1] = binCoord(lo.y, g.origin.y, g.size, g.ny);
    b.lo[2] = binCoord(lo.z, g.origin.z, g.size, g.nz);
    b.hi[0] = binCoord(hi.x, g.origin.x, g.size, g.nx);
    b.hi[1] = binCoord(hi.y, g.origin.y, g.size, g.ny);
    b.hi[2] = binCoord(hi.z, g.origin.z, g.size, g.nz);
    return b;
}

// Stores box b of item i as three lows and three highs (the layout both backends' bins use).
DEME_HD inline void storeBinBox(const BinBox& b, size_t i, int* lo, int* hi) {
    for (int a = 0; a < 3; a++) {
        lo[3 * i + a] = b.lo[a];
        hi[3 * i + a] = b.hi[a];
    }
}

}  // namespace deme
