// Contact detection in slabs of bin layers (docs/memory.md, "A detection's bins in slabs"). A
// detection's bins are dense over the grid: every bin's first entry (4 B a bin, for spheres and again
// for triangles) beside the entries. In a large scene that is 26-30 B a sphere, held beside the
// outbox's pairs: a synchronous detection's peak. Where spheres are binned by their centres
// (kinematics/DetectionRules.h, centreReach), the spheres whose centres lie in a slab of z layers
// find every partner in those layers and `halo` layers either side, so a slab's search needs the
// bins of those layers only: the detection makes them for one slab at a time, searches that slab's
// spheres, and goes on to the next. Every sphere is searched in exactly one slab and writes its
// partners at its own offset, so the pairs are the same, in the same order, whatever the slabs.
//
// Layers along z because z is the slowest axis of binIndex: a slab's bins are one contiguous range
// of bin indices, starting at BinsView::firstBin. Not along a periodic z (a slab's halo would wrap)
// nor in a sheared cell (its image layers' bins shift): there one slab, the whole grid. Which slabs
// a detection makes: runtime/DetectionSlabs.h.
#pragma once

#include "kinematics/BinGrid.h"

namespace deme {

// z layers [from, to) of a grid.
struct LayerRange {
    int from, to;
    DEME_HD bool holds(int z) const { return z >= from && z < to; }
};

// Whether r is every layer of g (then nothing is cut: along a periodic z a box reaches past it).
DEME_HD inline bool isWholeGrid(const BinGrid& g, const LayerRange& r) { return r.from <= 0 && r.to >= g.nz; }

// Box b cut to the layers of r along z; false if nothing of it is left.
DEME_HD inline bool clipToLayers(const BinGrid& g, BinBox& b, const LayerRange& r) {
    if (isWholeGrid(g, r)) return true;
    b.lo[2] = b.lo[2] > r.from ? b.lo[2] : r.from;
    b.hi[2] = b.hi[2] < r.to - 1 ? b.hi[2] : r.to - 1;
    return b.lo[2] <= b.hi[2];
}

// The index of layer z's first bin.
DEME_HD inline uint64_t firstBinOfLayer(const BinGrid& g, int z) {
    return (uint64_t)g.nx * (uint64_t)g.ny * (uint64_t)z;
}

// One slab: the spheres whose centres' bins lie in `searched` are searched against the bins of
// `binned` (searched grown by the halo, cut to the grid).
struct BinSlab {
    LayerRange searched, binned;
    DEME_HD uint64_t firstBin(const BinGrid& g) const { return firstBinOfLayer(g, binned.from); }
    DEME_HD uint64_t numBins(const BinGrid& g) const {
        return (uint64_t)g.nx * (uint64_t)g.ny * (uint64_t)(binned.to - binned.from);
    }
};

// The whole grid as one slab (every detection that is not made in slabs).
DEME_HD inline BinSlab wholeGridSlab(const BinGrid& g) { return BinSlab{{0, g.nz}, {0, g.nz}}; }

}  // namespace deme
