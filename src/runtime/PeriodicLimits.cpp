#include "runtime/PeriodicLimits.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <deme/Error.h>

#include "physics/Quaternion.h"
#include "runtime/TextFormat.h"

namespace deme {

namespace {

const char* const AXIS_NAMES[3] = {"x", "y", "z"};

double axisComponent(const float3& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }
double axisLength(const double3& l, int a) { return a == 0 ? l.x : a == 1 ? l.y : l.z; }

double largestRadius(const std::vector<float>& radii) {
    double r = 0.0;
    for (float x : radii) r = std::max(r, (double)x);
    return r;
}

}  // namespace

void checkPeriodicRadii(const PeriodicBox& p, const std::vector<float>& radii, const char* call) {
    const double rMax = largestRadius(radii);
    for (int a = 0; a < 3; a++) {
        if (!periodicAlong(p, a)) continue;
        const double L = axisLength(p.length, a);
        if (L < 6.0 * rMax)
            throwError(call, std::string("the domain is periodic along ") + AXIS_NAMES[a] + " with a period of " +
                                 std::to_string(L) + " m, under six times the largest sphere radius (" +
                                 std::to_string(rMax) + " m): a grain would touch its own images");
    }
}

void checkPeriodicScene(const SimState& s, const char* call) {
    const PeriodicBox& p = s.frame.periodic;
    if (p.shear && !(periodicAlong(p, 0) && periodicAlong(p, 2)))
        throwError(call, "SetPeriodicShear shears along x with its gradient along z: the domain must be periodic "
                         "along x and z (InstructBoxDomainPeriodicity(\"xz\") or \"xyz\")");
    if (!p.axes) return;
    checkPeriodicRadii(p, s.spheres.radius, call);
    for (size_t k = 0; k < s.analytical.size(); k++) {
        const bodyID_t o = s.analytical.owner[k];
        const float3 dir = rotateToGlobal(s.owners.oriQ[o], s.analytical.relDir[k]);
        const bool plane = s.analytical.type[k] == ANAL_PLANE;
        for (int a = 0; a < 3; a++) {
            if (!periodicAlong(p, a)) continue;
            const double along = std::fabs(axisComponent(dir, a)) / std::max(1e-30, (double)length(dir));
            if (plane && along > 1e-6)
                throwError(call, "analytical component " + std::to_string(k) + " is a plane with normal " + formatVector(dir) +
                                     ", not parallel to the periodic " + AXIS_NAMES[a] +
                                     " axis (InstructBoxDomainPeriodicity): a wall on a periodic face, or "
                                     "across a period, would cut it; take out walls on the periodic faces "
                                     "(InstructBoxDomainBoundingBC \"none\" or a plane per bounded face)");
            if (!plane && std::fabs(along - 1.0) > 1e-6)
                throwError(call, "analytical component " + std::to_string(k) + " is a cylinder with axis " + formatVector(dir) +
                                     ", not along the periodic " + AXIS_NAMES[a] +
                                     " axis (InstructBoxDomainPeriodicity): it would not be the same in every period");
        }
    }
}

void checkShearedGrid(const PeriodicBox& p, const BinGrid& g, const char* call) {
    // A sheared layer's x bins are a box's shifted by the offset and one bin wider (layerXBins); in
    // fewer than 6 bins along x they could wrap onto themselves.
    if (p.shear && g.nx < 6)
        throwError(call, "the sheared cell's period along x holds " + std::to_string(g.nx) +
                             " contact-detection bins, under the 6 SetPeriodicShear needs: a longer period, or a "
                             "smaller SetInitBinSize");
}

double periodicMarginCap(const SimState& s, const float* familyExtraMargin) {
    const PeriodicBox& p = s.frame.periodic;
    if (!p.axes) return std::numeric_limits<double>::infinity();
    double shortest = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; a++)
        if (periodicAlong(p, a)) shortest = std::min(shortest, axisLength(p.length, a));
    double extra = 0.0;
    for (unsigned int f = 0; f < NUM_FAMILIES; f++) extra = std::max(extra, (double)familyExtraMargin[f]);
    // 2 r + 2 (margin + extra) <= 0.9 L / 2.
    return std::max(0.0, 0.5 * (0.45 * shortest - 2.0 * largestRadius(s.spheres.radius)) - extra);
}

}  // namespace deme
