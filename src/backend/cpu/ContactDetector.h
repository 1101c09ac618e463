// Contact detection on the CPU: the per-item rules of kinematics/DetectionRules.h in OpenMP loops,
// with items sorted into bins by a counting sort. See that header for the method and the no-miss
// bound.
#pragma once

#include <vector>

#include "backend/cpu/DormantCache.h"
#include "runtime/IndexLimits.h"
#include "runtime/MemoryAccounting.h"
#include "kinematics/DetectionRules.h"
#include "state/SimState.h"

namespace deme {

// Candidate pairs, sorted by (geomA, geomB); geomB uses the unified geometry id space of SimState.
struct DetectedContacts {
    std::vector<bodyID_t> geomA, geomB;  // (a pair's type follows from B: state/ContactTypeOf.h)
    size_t size() const { return geomA.size(); }
    size_t bytes() const { return vectorBytes(geomA) + vectorBytes(geomB); }
};

// One thread's pairs while a search runs: B of each, and A either as each searched sphere's number
// of pairs (the thread searches its spheres in order, so its pairs are runs of one A: 4 B a sphere
// instead of 4 B a pair) or, where that is not smaller or the active box adds dormant partners
// (keyed by the lower id, sorted afterwards), A of each pair.
struct ThreadPairs {
    std::vector<bodyID_t> geomA, geomB;
    std::vector<uint32_t> runs;  // pairs per searched sphere, from the thread's first
    size_t firstSearched = 0;
    size_t size() const { return geomB.size(); }
    size_t bytes() const { return vectorBytes(geomA) + vectorBytes(geomB) + vectorBytes(runs); }
};

// Items registered in the bins their boxes touch (counting sort by bin).
struct BinRegistry {
    std::vector<uint32_t> start, entries;
    // Items ids[0, n) (0 .. n - 1 if ids is null), each in the bins of box(i) (a BinBox), stable in
    // item order, so each bin lists its items in increasing id. The boxes are computed twice (count,
    // then fill) rather than stored.
    template <class Box>
    void build(const BinGrid& grid, const bodyID_t* ids, size_t n, Box&& box);
    BinsView view() const { return BinsView{start.data(), entries.data()}; }
    size_t bytes() const { return vectorBytes(start) + vectorBytes(entries); }
    void release() {
        releaseVector(start);
        releaseVector(entries);
    }
};

template <class Box>
void BinRegistry::build(const BinGrid& grid, const bodyID_t* ids, size_t n, Box&& box) {
    const size_t nBins = (size_t)grid.numBins();
    start.assign(nBins + 1, 0);
    auto id = [ids](size_t k) { return ids ? (size_t)ids[k] : k; };
    for (size_t k = 0; k < n; k++)
        forEachBinOf(grid, box(id(k)), [&](int x, int y, int z) { start[binIndex(grid, x, y, z) + 1]++; });
    // The offsets are 32-bit: their total is kept in 64 bits too (runtime/IndexLimits.h), so that a
    // wrapped sum is an error.
    uint64_t total = 0;
    for (size_t b = 0; b < nBins; b++) {
        total += start[b + 1];
        start[b + 1] += start[b];
    }
    requireIndexable(total, "bin entries", FEWER_BIN_ENTRIES_REMEDY, "DoDynamics");
    entries.resize(start[nBins]);
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t k = 0; k < n; k++) {
        const size_t i = id(k);
        forEachBinOf(grid, box(i), [&](int x, int y, int z) { entries[fill[binIndex(grid, x, y, z)]++] = (uint32_t)i; });
    }
}

class ContactDetector {
  public:
    // familyMask: 256 x 256, nonzero where contacts between two families are resolved.
    // familyExtraMargin: 256 values added to the margin of every geometry of that family's owners.
    // Seconds spent binning and searching pairs are added to the two counters.
    void detect(const SimState& s, const BinGrid& grid, double margin, const uint8_t* familyMask,
                const float* familyExtraMargin, DetectedContacts& out, double& binningSeconds, double& searchSeconds);

    // The active box (docs/active-box.md): the dormant families, 1 per family, and those with a
    // prescribed velocity; after setGeometry, with the families in force (drops the cached registry).
    void setFamilies(const uint8_t* dormant, const uint8_t* prescribed, const SimState& live) {
        m_dormant.setFamilies(dormant, prescribed, live);
    }
    const DormantCache& dormantCache() const { return m_dormant; }
    // A detection's bins are let go at its end where they hold more than this many bytes (and kept
    // for the next one otherwise): a large scene keeps no bins through the steps between, a small
    // one no allocation per detection (docs/memory.md).
    void keepBinsUpTo(size_t bytes) { m_keepBinsUpTo = bytes; }
    // The scratch it keeps between detections (MemoryGroup::DETECTION).
    size_t bytes() const {
        size_t b = m_dormant.bytes() + m_spheres.bytes() + m_triangles.bytes() + vectorBytes(m_triLo) +
                   vectorBytes(m_triHi) + vectorBytes(m_threadOut);
        for (const ThreadPairs& t : m_threadOut) b += t.bytes();
        return b;
    }

  private:
    // Sorts the pairs by (A, B) (with dormant partners, found from the moving side).
    static void sortPairs(DetectedContacts& out);
    DormantCache m_dormant;
    // One detection's bins (rebuilt by every detection).
    BinRegistry m_spheres, m_triangles;
    size_t m_keepBinsUpTo = KEEP_REBUILT_ARRAYS_UP_TO;
    std::vector<double3> m_triLo, m_triHi;
    std::vector<ThreadPairs> m_threadOut;       // each thread's pairs, only while a detection runs
    size_t m_lastPairs = 0;                     // how many the last detection found
};

}  // namespace deme
