// Rigid-body kinematics and time integration of one owner: the integrator the owner step
// (dynamics/OwnerStep.h) calls on both backends.
//
// Integrator (documented in docs/physics.md): semi-implicit (symplectic) Euler for translation,
//   v(n+1) = v(n) + dt * a(n),   x(n+1) = x(n) + dt * v(n+1)        -- first order, energy-stable;
// explicit midpoint (second order) for Euler's rotation equations in the body frame,
//   I dw/dt = tau - w x (I w),
// and the exact exponential map of the midpoint angular velocity for the orientation quaternion
// (Quaternion.h: a series for the usual small angles, the exact form for large ones). Written with
// values and no branches, so that the owner sweep vectorises.
#pragma once

#include "Quaternion.h"

namespace deme {

// Global position of a point given in an owner's local frame.
DEME_HD inline double3 localPointToGlobal(const double3& ownerPos, const float4& q, const float3& local) {
    return ownerPos + rotateToGlobal(q, to_double3(local));
}

// Body-frame angular acceleration from Euler's equations with principal moments `moi`.
DEME_HD inline float3 eulerAngularAcc(const float3& w, const float3& torqueLocal, const float3& moi) {
    const float3 Iw = w * moi;
    return (torqueLocal - cross(w, Iw)) / moi;
}

// The same with the reciprocal moments given, for loops that reuse them (a multiply is several
// times cheaper than a divide).
DEME_HD inline float3 eulerAngularAccInv(const float3& w, const float3& torqueLocal, const float3& moi,
                                         const float3& invMoi) {
    const float3 Iw = w * moi;
    return (torqueLocal - cross(w, Iw)) * invMoi;
}

// Translation, semi-implicit Euler: the new velocity from the acceleration, then the new position
// from the new velocity.
DEME_HD inline float3 advanceVelocity(const float3& v, const float3& acc, float dt) { return v + dt * acc; }
DEME_HD inline double3 advancePosition(const double3& x, const float3& vNew, double dt) {
    return x + to_double3(vNew) * dt;
}

// Rotation, explicit midpoint: the body-frame angular velocity at the middle of the step (which the
// orientation update uses) and at its end.
struct AngularStep {
    float3 wMid, wEnd;
};
DEME_HD inline AngularStep advanceAngularVelocity(const float3& w, const float3& torqueLocal, const float3& moi,
                                                  const float3& invMoi, float dt) {
    AngularStep r;
    r.wMid = w + (0.5f * dt) * eulerAngularAccInv(w, torqueLocal, moi, invMoi);
    r.wEnd = w + dt * eulerAngularAccInv(r.wMid, torqueLocal, moi, invMoi);
    return r;
}

}  // namespace deme
