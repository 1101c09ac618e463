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
    // Lees–Edwards (SetPeriodicShear; periodic x and z): the images across the z faces slide along
    // x. The image of the cell above (z + Lz) moves at +shearVelocity (= rate * Lz) and is displaced
    // by shearOffsetAt(t) = shearVelocity * t, less whole periods Lx. The offset is read at time
    // shearTime, or, where shearClock is not null (a GPU's steps), at *shearClock, the step's clock in
    // device memory (replayed step graphs keep one view for every step).
    unsigned int shear;
    double shearVelocity;
    double shearTime;
    const double* shearClock;
};

DEME_HD_INLINE bool periodicAlong(const PeriodicBox& p, int axis) { return (p.axes >> axis) & 1u; }

// The x offset of the image above at time t, in [-Lx/2, Lx/2].
DEME_HD_INLINE double shearOffsetAt(const PeriodicBox& p, double t) {
    const double d = p.shearVelocity * t;
    return d - p.length.x * rint(d / p.length.x);
}
// The time the offset is read at now (the start of the step the steps are in).
DEME_HD_INLINE double shearTimeNow(const PeriodicBox& p) { return p.shearClock ? *p.shearClock : p.shearTime; }
DEME_HD_INLINE double shearOffsetNow(const PeriodicBox& p) { return shearOffsetAt(p, shearTimeNow(p)); }

// The multiple of the period nearest to an offset d along one axis (0 along a non-periodic axis).
DEME_HD_INLINE double imageShiftAxis(double d, double length, bool periodic) {
    return periodic ? length * rint(d / length) : 0.0;
}

// For an offset d = a - b between two points: the shift s such that b + s is the image of b nearest
// to a (zero without periodic axes). In a sheared cell an image k cells above (k = s.z / Lz) is also
// displaced by k times the offset along x.
DEME_HD_INLINE double3 imageShift(const PeriodicBox& p, const double3& d) {
    if (!p.axes) return make_double3(0.0, 0.0, 0.0);
    const double sz = imageShiftAxis(d.z, p.length.z, periodicAlong(p, 2));
    const double ox = p.shear ? rint(sz / p.length.z) * shearOffsetNow(p) : 0.0;
    return make_double3(ox + imageShiftAxis(d.x - ox, p.length.x, periodicAlong(p, 0)),
                        imageShiftAxis(d.y, p.length.y, periodicAlong(p, 1)), sz);
}

// The velocity an image taken by `shift` (imageShift) has beyond its original's: k times the shear
// velocity along x for an image k cells above; zero without shear.
DEME_HD_INLINE float3 imageVelocity(const PeriodicBox& p, const double3& shift) {
    return make_float3(p.shear ? (float)(rint(shift.z / p.length.z) * p.shearVelocity) : 0.f, 0.f, 0.f);
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

// An owner at x after a step of length dt, wrapped into the domain along its periodic axes. In a
// sheared cell one that left through a z face enters through the other displaced along x by the
// offset at the step's end and with the shear velocity taken off (through the top) or added (through
// the bottom), returned in dvx (0 otherwise). Selects, not branches: the CPU's owner sweep
// vectorises through this; the offset (and a GPU's clock) is read only for an owner that crossed.
DEME_HD_INLINE double3 wrapIntoDomain(const PeriodicBox& p, const double3& x, const double3& lo, double dt,
                                      float& dvx) {
    const double above = x.z < lo.z ? -1.0 : x.z >= lo.z + p.length.z ? 1.0 : 0.0;  // cells above it is in
    const double k = p.shear ? above : 0.0;
    const double offset = k != 0.0 ? shearOffsetAt(p, shearTimeNow(p) + dt) : 0.0;
    dvx = (float)(-k * p.shearVelocity);
    return make_double3(wrapAxis(x.x - k * offset, lo.x, p.length.x, periodicAlong(p, 0)),
                        wrapAxis(x.y, lo.y, p.length.y, periodicAlong(p, 1)),
                        wrapAxis(x.z, lo.z, p.length.z, periodicAlong(p, 2)));
}

}  // namespace deme
