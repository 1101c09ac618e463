// Contact detection on the CPU: the per-item rules of kinematics/DetectionRules.h in OpenMP loops,
// with items sorted into bins by a counting sort. See that header for the method and the no-miss
// bound.
#pragma once

#include <vector>

#include "kinematics/DetectionRules.h"
#include "state/SimState.h"

namespace deme {

// Candidate pairs, sorted by (geomA, geomB); geomB uses the unified geometry id space of SimState.
struct DetectedContacts {
    std::vector<bodyID_t> geomA, geomB;
    std::vector<uint8_t> type;
    size_t size() const { return geomA.size(); }
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
    BinsView view() const { return BinsView{lo.data(), hi.data(), start.data(), entries.data()}; }
};

class ContactDetector {
  public:
    // familyMask: 256 x 256, nonzero where contacts between two families are resolved.
    // familyExtraMargin: 256 values added to the margin of every geometry of that family's owners.
    // Seconds spent binning and searching pairs are added to the two counters.
    void detect(const SimState& s, const BinGrid& grid, double margin, const uint8_t* familyMask,
                const float* familyExtraMargin, DetectedContacts& out, double& binningSeconds, double& searchSeconds);

  private:
    // Scratch buffers reused between detections.
    BinRegistry m_spheres, m_triangles;
    std::vector<double3> m_triLo, m_triHi;
    std::vector<DetectedContacts> m_threadOut;
};

}  // namespace deme
