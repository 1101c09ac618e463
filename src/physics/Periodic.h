// Periodic boundaries (InstructBoxDomainPeriodicity): along a periodic axis the domain's two faces
// are one, a grain that leaves through one enters through the other, and two geometries interact
// through their nearest images (the minimum-image convention). Per-item functions for the CPU's
// loops and the GPU's kernels alike (NVRTC compiles this header).
//
// Positions: owners are kept inside the domain along periodic axes (wrapped after each step); a
// clump's spheres and a mesh's triangles are placed from their owner and may reach beyond a face.
// Every comparison of two geometries takes the image of one nearest to the other, which is exact
// as long as no interaction reaches half a period (checked at Initialize, and the contact margin is
// capped so that detection never needs more: runtime/DetectionSchedule.h).
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

struct PeriodicBox {
    double3 length;     // the domain's edges (the periods along periodic axes)
    unsigned int axes;  // bit a set: axis a (x = 0, y = 1, z = 2) is periodic
};

DEME_HD_INLINE bool periodicAlong(const PeriodicBox& p, int axis) { return (p.axes >> axis) & 1u; }

// The multiple of the period nearest to an offset d along one axis (0 along a non-periodic axis).
DEME_HD_INLINE double imageShiftAxis(double d, double length, bool periodic) {
    return periodic ? length * rint(d / length) : 0.0;
}

// For an offset d = a - b between two points: the shift s such that b + s is the image of b nearest
// to a (zero without periodic axes).
DEME_HD_INLINE double3 imageShift(const PeriodicBox& p, const double3& d) {
    if (!p.axes) return make_double3(0.0, 0.0, 0.0);
    return make_double3(imageShiftAxis(d.x, p.length.x, periodicAlong(p, 0)),
                        imageShiftAxis(d.y, p.length.y, periodicAlong(p, 1)),
                        imageShiftAxis(d.z, p.length.z, periodicAlong(p, 2)));
}

// The image of point b nearest to point a. Without periodic axes, b itself at the cost of one test:
// detection and the force pass call this for every candidate pair, and the scene-wide flag is the
// same for every thread.
DEME_HD_INLINE double3 nearestImage(const PeriodicBox& p, const double3& a, const double3& b) {
    return p.axes ? b + imageShift(p, a - b) : b;
}

// x wrapped into [lo, lo + length) along periodic axes (a grain that left through one face enters
// through the other); unchanged along the others. Written without branches for the owner sweep.
DEME_HD_INLINE double wrapAxis(double x, double lo, double length, bool periodic) {
    const double below = x < lo ? length : 0.0;
    const double above = x >= lo + length ? -length : 0.0;
    return periodic ? x + below + above : x;
}

DEME_HD_INLINE double3 wrapIntoDomain(const PeriodicBox& p, const double3& x, const double3& lo) {
    return make_double3(wrapAxis(x.x, lo.x, p.length.x, periodicAlong(p, 0)),
                        wrapAxis(x.y, lo.y, p.length.y, periodicAlong(p, 1)),
                        wrapAxis(x.z, lo.z, p.length.z, periodicAlong(p, 2)));
}

}  // namespace deme
