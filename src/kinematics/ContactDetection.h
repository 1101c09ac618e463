// Contact detection (the kinematics side, paper §2.1): finds every geometry pair whose surfaces are
// closer than twice the margin, on a uniform bin grid.
//
// No-miss bound: every geometry is enlarged by `margin`. A pair left out is more than 2*margin apart.
// The step loop re-detects before any owner's accumulated travel (an upper bound on how far any of
// its surface points moved) exceeds the margin, so such a pair cannot touch before the next
// detection: the gap can shrink by at most travelA + travelB <= 2*margin.
#pragma once

#include <vector>

#include "runtime/SimState.h"

namespace deme {

struct BinGrid {
    double3 origin;
    double size = 0.0;
    int64_t nx = 0, ny = 0, nz = 0;
    size_t numBins() const { return (size_t)(nx * ny * nz); }
};

// Bins cover the domain. Bin edge: the user's size if given, else twice the largest sphere radius,
// enlarged if needed so that there are at most ~8 bins per sphere.
BinGrid makeBinGrid(const SimState& s, double requestedSize);

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
    void setBox(const BinGrid& grid, size_t i, const double3& boxLo, const double3& boxHi);
    void build(const BinGrid& grid, size_t n);
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
