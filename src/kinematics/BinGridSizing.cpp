#include "kinematics/BinGridSizing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace deme {

namespace {

struct RadiusGroup {
    double diameter = 0.0;
    double count = 0.0;
};

// The spheres as (diameter, count) groups: one per distinct radius, or, for a continuous size
// distribution, one per 1/64 of the log range between the smallest and the largest.
std::vector<RadiusGroup> radiusGroups(const std::vector<float>& radii) {
    std::map<float, double> distinct;
    for (float r : radii) {
        distinct[r] += 1.0;
        if (distinct.size() > 64) break;
    }
    std::vector<RadiusGroup> groups;
    if (distinct.size() <= 64) {
        for (const auto& [r, n] : distinct) groups.push_back({2.0 * r, n});
        return groups;
    }
    const auto [lo, hi] = std::minmax_element(radii.begin(), radii.end());
    const double logLo = std::log((double)*lo), span = std::max(1e-12, std::log((double)*hi) - logLo);
    groups.resize(64);
    for (size_t k = 0; k < 64; k++) groups[k].diameter = 2.0 * std::exp(logLo + span * (k + 1) / 64.0);
    for (float r : radii) groups[std::min<size_t>(63, (size_t)((std::log((double)r) - logLo) / span * 64.0))].count += 1.0;
    return groups;
}

// Work of a detection with bin edge `size`, in units of one bin registration: every sphere is
// registered in the (d / size + 1)^3 bins its box may touch, and the pairs tested are about R^2 / 2
// per occupied bin, the occupied bins being the spheres' own volume (sum of d^3) in bins.
double detectionCost(const std::vector<RadiusGroup>& groups, double size) {
    double registrations = 0.0, volume = 0.0;
    for (const RadiusGroup& g : groups) {
        const double perAxis = g.diameter / size + 1.0;
        registrations += g.count * perAxis * perAxis * perAxis;
        volume += g.count * g.diameter * g.diameter * g.diameter;
    }
    const double occupiedBins = std::max(1.0, volume / (size * size * size));
    return registrations + registrations * registrations / (2.0 * occupiedBins);
}

}  // namespace

double defaultBinSize(const std::vector<float>& radii) {
    if (radii.empty()) return 0.0;
    // Candidate edges: twice each group's radius. One size gives 2 r, the size of the past rule;
    // a few large spheres among many small ones no longer make every bin as large as they are.
    const std::vector<RadiusGroup> groups = radiusGroups(radii);
    double best = 0.0, bestCost = 0.0;
    for (const RadiusGroup& g : groups) {
        const double cost = detectionCost(groups, g.diameter);
        if (best == 0.0 || cost < bestCost) best = g.diameter, bestCost = cost;
    }
    return best;
}

BinGrid makeBinGrid(const SimState& s, double requestedSize) {
    BinGrid g{};
    g.origin = s.frame.origin;
    double size = requestedSize;
    if (size <= 0.0) {
        size = defaultBinSize(s.spheres.radius);
        const double volume = s.domainSize.x * s.domainSize.y * s.domainSize.z;
        const double nTarget = 8.0 * (double)std::max<size_t>(s.spheres.size(), 1);
        size = std::max(size, std::cbrt(volume / nTarget));
        // A sheared cell needs 6 bins or more along x (kinematics/BinGrid.h, layerXBins).
        if (s.frame.periodic.shear) size = std::min(size, s.domainSize.x / 6.0);
    }
    // Never more bins along an axis than positions can distinguish.
    size = std::max(size, std::max({s.domainSize.x, s.domainSize.y, s.domainSize.z}) / 1e6);
    g.size = size;
    g.periodic = s.frame.periodic.axes;
    g.shear = s.frame.periodic.shear;  // its offset is each detection's (ContactDetector, CudaKinematics)
    // A bounded axis: bins of `size`, the last one reaching beyond the face. A periodic axis: whole
    // bins tile the period, each a little more than `size`, so that a box reaching over a face
    // continues in the bins at the other face.
    auto axis = [&](double length, int a, double& edge) {
        if (!((g.periodic >> a) & 1u)) {
            edge = size;
            return std::max(1, (int)std::ceil(length / size));
        }
        const int n = std::max(1, (int)std::floor(length / size));
        edge = length / n;
        return n;
    };
    g.nx = axis(s.domainSize.x, 0, g.edge.x);
    g.ny = axis(s.domainSize.y, 1, g.edge.y);
    g.nz = axis(s.domainSize.z, 2, g.edge.z);
    return g;
}

}  // namespace deme
