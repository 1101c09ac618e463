// The uniform bin grid of contact detection (paper §2.1) and the per-item arithmetic on it, for the
// CPU's loops and the GPU's kernels alike (NVRTC compiles this header).
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

struct BinGrid {
    double3 origin;
    double size;  // the bin edge chosen (by the sizing rule or SetInitBinSize)
    // The bins' edges along x, y, z: `size`, except along a periodic axis, where whole bins tile the
    // period (a little more than `size`; bins wrap around there).
    double3 edge;
    int nx, ny, nz;
    unsigned int periodic;  // bit a: axis a is periodic
    // Lees–Edwards (physics/Periodic.h): the layers of bins beyond a z face are images displaced
    // along x by shearOffset (the offset of the image above, at the detection's snapshot).
    unsigned int shear;
    double shearOffset;
    DEME_HD uint64_t numBins() const { return (uint64_t)nx * (uint64_t)ny * (uint64_t)nz; }
};

// The bin coordinate of x along `axis`. Along a bounded axis it is clamped to the grid: geometries
// beyond the domain (a mesh that reaches out of it) register in the border bins. Along a periodic
// axis it is not (a box reaching over a face starts at -1 or ends at n): binIndex wraps it into the
// bins at the other face.
DEME_HD inline int binCoord(const BinGrid& g, int axis, double x) {
    const double origin = axis == 0 ? g.origin.x : axis == 1 ? g.origin.y : g.origin.z;
    const double edge = axis == 0 ? g.edge.x : axis == 1 ? g.edge.y : g.edge.z;
    const int n = axis == 0 ? g.nx : axis == 1 ? g.ny : g.nz;
    const double f = floor((x - origin) / edge);
    if ((g.periodic >> axis) & 1u) return f > (double)-n && f < 2.0 * n ? (int)f : 0;  // NaN: 0
    if (!(f > 0.0)) return 0;  // also maps NaN to 0; NaN positions are caught by the integrator
    if (f >= (double)(n - 1)) return n - 1;
    return (int)f;
}

// A periodic axis's bin coordinate in (-n, 2n) wrapped into [0, n).
DEME_HD inline int wrapBin(int c, int n) { return c < 0 ? c + n : c >= n ? c - n : c; }

// 64-bit on the host; 32-bit in GPU code, where 64-bit multiplies are several instructions in the
// pair search's inner loops and exact anyway: the CUDA backend refuses grids of 2^32 bins or more
// (its bin keys are 32-bit). Coordinates along periodic axes are wrapped first.
DEME_HD inline uint64_t binIndex(const BinGrid& g, int x, int y, int z) {
    if (g.periodic) {
        x = (g.periodic & 1u) ? wrapBin(x, g.nx) : x;
        y = (g.periodic & 2u) ? wrapBin(y, g.ny) : y;
        z = (g.periodic & 4u) ? wrapBin(z, g.nz) : z;
    }
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

// Along a periodic axis a box is widened by a billionth of a bin: an item and the image of it that
// a search compares are a whole number of periods apart only up to rounding, and a box that ends on
// a bin boundary must be registered in every bin either side of the rounding sees it in.
DEME_HD inline BinBox binBox(const BinGrid& g, const double3& lo, const double3& hi) {
    const double sx = (g.periodic & 1u) ? 1e-9 * g.edge.x : 0.0, sy = (g.periodic & 2u) ? 1e-9 * g.edge.y : 0.0,
                 sz = (g.periodic & 4u) ? 1e-9 * g.edge.z : 0.0;
    BinBox b;
    b.lo[0] = binCoord(g, 0, lo.x - sx);
    b.lo[1] = binCoord(g, 1, lo.y - sy);
    b.lo[2] = binCoord(g, 2, lo.z - sz);
    b.hi[0] = binCoord(g, 0, hi.x + sx);
    b.hi[1] = binCoord(g, 1, hi.y + sy);
    b.hi[2] = binCoord(g, 2, hi.z + sz);
    // A box that spans a whole period (a cell of one or two bins along an axis, or a sphere as wide
    // as the cell) is cut to that period's bins, each once: listed twice, a bin would register an
    // item twice and report its pairs twice. Not in a sheared cell (its image layers' bins shift).
    if (g.periodic && !g.shear) {
        const int n[3] = {g.nx, g.ny, g.nz};
        for (int a = 0; a < 3; a++)
            if (((g.periodic >> a) & 1u) && b.hi[a] - b.lo[a] + 1 >= n[a]) {
                b.lo[a] = 0;
                b.hi[a] = n[a] - 1;
            }
    }
    return b;
}

// Which image a layer z of bins is in (z unwrapped, as the boxes store it): -1 below the bottom
// face, 1 above the top one, 0 inside.
DEME_HD inline int layerImage(const BinGrid& g, int z) { return z < 0 ? -1 : z >= g.nz ? 1 : 0; }

// The x bins [xa, xb] that layer z of a box with x bins [x0, x1] covers. In a sheared cell a layer
// beyond a z face is the image layer at the other face, where the box lies displaced along x by minus
// the offset times the layer's image: there it covers the bins of [x0, x1] shifted by the offset's
// whole bins and one bin more (whatever the fraction, the shifted box lies within), brought into
// [0, 2 nx) for binIndex. Registration and search take the same ranges, and binOwnsPair picks one
// bin of them per pair, so a pair is still found once.
DEME_HD inline void layerXBins(const BinGrid& g, int z, int x0, int x1, int& xa, int& xb) {
    const int k = g.shear ? layerImage(g, z) : 0;
    if (k == 0) {
        xa = x0;
        xb = x1;
        return;
    }
    const int d = (int)floor(-(double)k * g.shearOffset / g.edge.x);
    xa = x0 + d;
    xb = x1 + d + 1;
    while (xa < 0) xa += g.nx, xb += g.nx;
    while (xa >= g.nx) xa -= g.nx, xb -= g.nx;
}

// How many rows of bins (one y and one z, every x) box b covers.
DEME_HD inline unsigned int binRows(const BinBox& b) {
    return (unsigned int)((b.hi[1] - b.lo[1] + 1) * (b.hi[2] - b.lo[2] + 1));
}

// The bins of rows first, first + step, first + 2 step, ... of box b (rows in (z, y) order, each
// row's bins in x order): f(x, y, z) for each. Several threads that take the rows of one box in turn
// (first = 0 .. step - 1) cover its bins once between them (the GPU's lab-scale detection,
// docs/cuda-backend.md).
template <class F>
DEME_HD inline void forEachBinOfRows(const BinGrid& g, const BinBox& b, unsigned int first, unsigned int step, F&& f) {
    const unsigned int ny = (unsigned int)(b.hi[1] - b.lo[1] + 1), rows = binRows(b);
    int xa, xb;  // a layer's x bins (shifted in a sheared cell's image layers: layerXBins)
    for (unsigned int r = first; r < rows; r += step) {
        const int y = b.lo[1] + (int)(r % ny), z = b.lo[2] + (int)(r / ny);
        for (layerXBins(g, z, b.lo[0], b.hi[0], xa, xb); xa <= xb; xa++) f(xa, y, z);
    }
}

// The bins box b covers, in (z, y, x) order: f(x, y, z) for each. Registration and search walk the
// same bins this way on both backends.
template <class F>
DEME_HD inline void forEachBinOf(const BinGrid& g, const BinBox& b, F&& f) {
    forEachBinOfRows(g, b, 0u, 1u, f);
}

}  // namespace deme
