// Contact detection on the CPU: the per-item rules of kinematics/DetectionRules.h in OpenMP loops,
// with items sorted into bins by a counting sort. See that header for the method and the no-miss
// bound.
#pragma once

#include <vector>

#include "backend/cpu/DormantCache.h"
#include "runtime/MemoryAccounting.h"
#include "kinematics/DetectionRules.h"
#include "state/SimState.h"

namespace deme {

// Candidate pairs, sorted by (geomA, geomB); geomB uses the unified geometry id space of SimState.
struct DetectedContacts {
    std::vector<bodyID_t> geomA, geomB;
    std::vector<uint8_t> type;
    size_t size() const { return geomA.size(); }
    size_t bytes() const { return vectorBytes(geomA) + vectorBytes(geomB) + vectorBytes(type); }
};

// Items registered in the bins their boxes touch (counting sort by bin).
struct BinRegistry {
    std::vector<int32_t> lo, hi;  // 3 bin coordinates per item
    std::vector<uint32_t> start, entries;
    void resize(size_t n) {
        lo.resize(3 * n);
        hi.resize(3 * n);
    }
    // Stable in item order, so each bin lists its items in increasing id.
    void build(const BinGrid& grid, size_t n);
    // The same for the items ids[0, n) only (their lo/hi at their own ids).
    void build(const BinGrid& grid, const bodyID_t* ids, size_t n);
    BinsView view() const { return BinsView{lo.data(), hi.data(), start.data(), entries.data()}; }
    size_t bytes() const { return vectorBytes(lo) + vectorBytes(hi) + vectorBytes(start) + vectorBytes(entries); }
};

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
    // The scratch it keeps between detections (MemoryGroup::DETECTION).
    size_t bytes() const {
        size_t b = m_dormant.bytes() + vectorBytes(m_keys) + m_spheres.bytes() + m_triangles.bytes() +
                   vectorBytes(m_triLo) + vectorBytes(m_triHi) + vectorBytes(m_threadOut);
        for (const DetectedContacts& t : m_threadOut) b += t.bytes();
        return b;
    }

  private:
    // Sorts the pairs by (A, B) (with dormant partners, found from the moving side).
    void sortPairs(const SimState& s, DetectedContacts& out);
    DormantCache m_dormant;
    std::vector<uint64_t> m_keys;
    // Scratch buffers reused between detections.
    BinRegistry m_spheres, m_triangles;
    std::vector<double3> m_triLo, m_triHi;
    std::vector<DetectedContacts> m_threadOut;  // each thread's pairs, only while a detection runs
    size_t m_lastPairs = 0;                     // how many the last detection found
};

}  // namespace deme
