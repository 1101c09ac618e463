// How the GPU's contact detection spreads a sphere's work over threads at lab scale
// (kernels/Detection.cu; docs/cuda-backend.md, "Detection at lab scale"). There a detection is
// latency bound: its time is the longest chain of dependent loads any one thread walks. A thread
// walking the hundreds of bins of a large sphere's box (a 20 mm ball among 1 mm grains spans some
// 1,500 bins of 2 mm) was one such chain, and a grain's search at a wide margin (the impact's 0.55
// mm: a 3.1 mm box of 8-27 bins with some 20 entries each) another (BENCHMARKS.md, SMALL-SYSTEMS).
//   - Registration (deme_bin_count, deme_bin_scatter): `binningLanes` threads an item, each taking
//     every lanes-th row of bins of its box.
//   - Pair search: `searchLanes` threads a sphere (deme_pair_search_lanes), and the wide spheres
//     (radius at least wideSphereRadius) WIDE_SPHERE_LANES threads each (deme_pair_search_wide).
// Large scenes fill the GPU with a thread an item and keep it (the wide spheres excepted). Inline
// and without CUDA, so that it is tested without a GPU.
#pragma once

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include <deme/Error.h>

#include "kinematics/BinGrid.h"

namespace deme::cuda {

// Below this many searched spheres a detection's kernels are a few short waves (as for the step's
// kernels, StepGraph.h).
constexpr unsigned int DETECTION_LANES_BELOW = 1u << 18;
constexpr unsigned int MAX_BINNING_LANES = 16;
constexpr unsigned int MAX_SEARCH_LANES = 16;
constexpr unsigned int WIDE_SPHERE_LANES = 32;  // a warp

// The most rows of bins (one y and one z) the box of a sphere of enlarged radius `reach` covers.
inline unsigned int maxBinRows(const BinGrid& g, double reach) {
    const double ny = std::floor(2.0 * reach / g.edge.y) + 2.0, nz = std::floor(2.0 * reach / g.edge.z) + 2.0;
    const double rows = std::fmin((double)g.ny, ny) * std::fmin((double)g.nz, nz);
    return rows >= 1e9 ? 1000000000u : (unsigned int)std::fmax(1.0, rows);
}

namespace detail {
// A diagnostic switch's whole number from `lo` to `hi`, or `fallback` where the variable is unset.
inline unsigned int envCount(const char* name, unsigned int lo, unsigned int hi, unsigned int fallback) {
    const char* v = std::getenv(name);
    if (!v || !*v) return fallback;
    char* end = nullptr;
    const unsigned long n = std::strtoul(v, &end, 10);
    if (*end || *v == '-' || n < lo || n > hi)
        throwError("DoDynamics", std::string(name) + " is '" + v + "', not a whole number from " + std::to_string(lo) +
                                     " to " + std::to_string(hi));
    return (unsigned int)n;
}

// One thread per row of a box of `rows` rows, at most `most`, below DETECTION_LANES_BELOW searched
// spheres; else 1, and 1 with the active box's dormant registry (its searches take one thread a
// sphere); the diagnostic switch `name` (1 to 64) sets the number instead, for any size.
inline unsigned int lanesFor(unsigned int searched, bool dormantRegistry, unsigned int rows, unsigned int most,
                             const char* name) {
    if (dormantRegistry) return 1;
    const unsigned int lanes = searched >= DETECTION_LANES_BELOW ? 1u : rows < most ? rows : most;
    return envCount(name, 1, 64, lanes);
}
}  // namespace detail

// Threads an item in registration, for `searched` spheres whose largest enlarged radius is
// `maxReach`: one per row of the largest box, at most MAX_BINNING_LANES, below DETECTION_LANES_BELOW
// spheres; else 1. With the active box's dormant registry 1. DEME_CUDA_BINNING_LANES (1 to 64) sets
// the number instead, for any size (a diagnostic switch; 1 is a thread an item).
inline unsigned int binningLanes(unsigned int searched, bool dormantRegistry, const BinGrid& g, double maxReach) {
    return detail::lanesFor(searched, dormantRegistry, maxBinRows(g, maxReach), MAX_BINNING_LANES,
                            "DEME_CUDA_BINNING_LANES");
}

// Threads a sphere in the pair search, for `searched` spheres of which the smallest enlarged radius
// is `minReach`: one per row of the smallest box, at most MAX_SEARCH_LANES, below
// DETECTION_LANES_BELOW spheres; else 1 (and 1 with the dormant registry). The smallest box, not the
// largest: lanes beyond a sphere's rows have nothing to do but still take a thread's place in the
// grid. DEME_CUDA_SEARCH_LANES (1 to 64) sets the number instead (a diagnostic switch).
inline unsigned int searchLanes(unsigned int searched, bool dormantRegistry, const BinGrid& g, double minReach) {
    return detail::lanesFor(searched, dormantRegistry, maxBinRows(g, minReach), MAX_SEARCH_LANES,
                            "DEME_CUDA_SEARCH_LANES");
}

// Whether the spheres may be binned by their centres (kinematics/DetectionRules.h, where none
// reaches far beyond a bin): from DETECTION_LANES_BELOW searched spheres, where a thread searches a
// sphere and the bins' bytes count (45.8 M spheres: 30 device bytes a sphere less and the search
// twice as fast, BENCHMARKS.md, MEMORY). Below, by their boxes, whose rows the lanes split as
// measured (a centre's search box, grown by the largest reach, has more rows than a grain's own
// box, which sets the lanes). DEME_CUDA_CENTRE_BINNING=1 allows it at any size, 0 never (diagnostic
// switches).
inline bool centreBinning(unsigned int searched) {
    return detail::envCount("DEME_CUDA_CENTRE_BINNING", 0, 1, searched >= DETECTION_LANES_BELOW ? 1u : 0u) == 1u;
}

// The radius from which a sphere is wide: twice the grid's smallest bin edge, so that its box spans
// at least 4 bins an axis (64 bins); the grains of a scene sized by the sizing rule span 2-3.
// Infinite (none is wide) with DEME_CUDA_WIDE_SPHERES=0 (a diagnostic switch).
inline float wideSphereRadius(const BinGrid& g) {
    if (detail::envCount("DEME_CUDA_WIDE_SPHERES", 0, 1, 1) == 0) return std::numeric_limits<float>::infinity();
    return (float)(2.0 * std::fmin(g.edge.x, std::fmin(g.edge.y, g.edge.z)));
}

}  // namespace deme::cuda
