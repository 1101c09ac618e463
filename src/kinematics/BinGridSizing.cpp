#include "kinematics/BinGridSizing.h"

#include <algorithm>
#include <cmath>

namespace deme {

BinGrid makeBinGrid(const SimState& s, double requestedSize) {
    BinGrid g;
    g.origin = s.frame.origin;
    double size = requestedSize;
    if (size <= 0.0) {
        float rmax = 0.f;
        for (float r : s.spheres.radius) rmax = std::max(rmax, r);
        size = 2.0 * rmax;
        const double volume = s.domainSize.x * s.domainSize.y * s.domainSize.z;
        const double nTarget = 8.0 * (double)std::max<size_t>(s.spheres.size(), 1);
        size = std::max(size, std::cbrt(volume / nTarget));
    }
    // Never more bins along an axis than positions can distinguish.
    size = std::max(size, std::max({s.domainSize.x, s.domainSize.y, s.domainSize.z}) / 1e6);
    g.size = size;
    g.nx = std::max(1, (int)std::ceil(s.domainSize.x / size));
    g.ny = std::max(1, (int)std::ceil(s.domainSize.y / size));
    g.nz = std::max(1, (int)std::ceil(s.domainSize.z / size));
    return g;
}

}  // namespace deme
