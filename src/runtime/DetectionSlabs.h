// Which slabs of bin layers a detection makes its bins in (kinematics/BinSlabs.h, docs/memory.md,
// "A detection's bins in slabs"): the GPU's detection (backend/cuda/CudaKinematics.cpp) and the
// memory estimate (runtime/MemoryEstimate.cpp) plan them alike.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "kinematics/BinSlabs.h"
#include "runtime/EnvironmentCount.h"

namespace deme {

// Whether a grid may be searched in slabs: spheres binned by their centres (centreReach > 0), z not
// periodic, no shear.
inline bool slabsPossible(const BinGrid& g, double centreReach) {
    return centreReach > 0.0 && !((g.periodic >> 2) & 1u) && !g.shear;
}

// The halo in layers. A partner's centre is within 2 centreReach of the searched sphere's (each
// enlarged radius is at most centreReach), and the bins a search walks lie within its centre plus its
// enlarged radius plus centreReach (searchedSphere): both at most ceil(2 centreReach / edge) layers
// away from the centre's own layer, for any centre (a floor moves by at most the ceiling of the
// distance). The millionth of a layer covers the rounding of the layer arithmetic, whose relative
// error is about 1e-16 of at most 2^32 layers.
inline int slabHalo(const BinGrid& g, double centreReach) {
    return (int)std::ceil(2.0 * centreReach / g.edge.z + 1e-6);
}

// Slab k of `slabs` (equal in layers, the last ones taking the remainder) with halo `halo`.
inline BinSlab binSlab(const BinGrid& g, int halo, int slabs, int k) {
    const int from = (int)((int64_t)g.nz * k / slabs), to = (int)((int64_t)g.nz * (k + 1) / slabs);
    return BinSlab{{from, to}, {std::max(0, from - halo), std::min(g.nz, to + halo)}};
}

// A detection's bins beyond which they are made in slabs: 4 B a searched sphere, and never below 32
// MiB (a scene of a few million spheres keeps one pass over its whole grid).
constexpr double SLAB_BIN_BYTES_PER_SPHERE = 4.0;
constexpr double SLAB_BIN_BYTES_AT_LEAST = 32.0 * 1024 * 1024;

// The bytes a detection's bins hold at once in `slabs` slabs: the thickest slab's starts (`kinds`
// arrays) and its share of the entries (taken as spread evenly over the layers).
inline double slabBinBytes(const BinGrid& g, double centreReach, int slabs, int kinds, double entries) {
    if (slabs <= 1) return 4.0 * (double)kinds * ((double)g.numBins() + 2.0) + 4.0 * entries;
    const int halo = slabHalo(g, centreReach);
    int thickest = 0;
    for (int k = 0; k < slabs; k++) {
        const BinSlab s = binSlab(g, halo, slabs, k);
        thickest = std::max(thickest, s.binned.to - s.binned.from);
    }
    const double share = (double)thickest / (double)g.nz;
    return 4.0 * (double)kinds * ((double)g.nx * g.ny * thickest + 2.0) + 4.0 * entries * share;
}

// How many slabs a detection makes its bins in. Slabs cost time: each slab's bins are made twice and
// every sphere is looked at once a slab and a pass (on one H100 the early mixer's two detections
// took 0.68 s in slabs against 0.53 s over the whole grid, the run 11 % slower: docs/memory.md), so
// a detection makes them only where its whole grid's bins (`kinds` start arrays of numBins + 2
// entries, 4 B each, and `entries` item entries), beside the `besides` bytes it will hold with them
// (its offsets and the outbox's pairs), would not fit in 9/10 of `freeBytes` (the device's free
// memory as it starts). Then the fewest equal slabs whose thickest does fit (fewer slabs, less time),
// and at most as many as make each about the bound above, or keep each four halos' worth of layers
// of its own (a thinner slab's halo costs more than it saves): so many where none fits, and where
// `freeBytes` is 0, which plans for a device that holds no more than it must (the memory estimate).
// 1 where slabs are not possible or the whole grid's bins are within the bound.
// DEME_DETECTION_SLABS=n asks for n slabs wherever they are possible (at most a layer each; the
// tests' comparisons), 0 or 1 for none.
inline int detectionSlabCount(const BinGrid& g, double centreReach, int kinds, double entries, double searchedSpheres,
                              double besides = 0.0, double freeBytes = 0.0) {
    if (!slabsPossible(g, centreReach) || g.nz < 2) return 1;
    size_t asked = 0;
    const char* v = std::getenv("DEME_DETECTION_SLABS");  // set but empty: as if unset
    if (v && *v && environmentCount("DEME_DETECTION_SLABS", "DoDynamics", "a number of slabs", asked))
        return (int)std::max<size_t>(1, std::min(asked, (size_t)g.nz));
    const double whole = slabBinBytes(g, centreReach, 1, kinds, entries);
    if (whole + besides <= 0.9 * freeBytes) return 1;
    const double bound = std::max(SLAB_BIN_BYTES_AT_LEAST, SLAB_BIN_BYTES_PER_SPHERE * searchedSpheres);
    if (whole <= bound) return 1;
    const int thinnest = 4 * std::max(1, slabHalo(g, centreReach));
    const int most = (int)std::min((double)std::max(1, g.nz / thinnest), std::ceil(whole / bound));
    for (int k = 2; k < most; k++)
        if (slabBinBytes(g, centreReach, k, kinds, entries) + besides <= 0.9 * freeBytes) return k;
    return most;
}

}  // namespace deme
