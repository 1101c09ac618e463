// Rigid-body kinematics and time integration of one owner.
//
// Integrator (documented in docs/physics.md): semi-implicit (symplectic) Euler for translation,
//   v(n+1) = v(n) + dt * a(n),   x(n+1) = x(n) + dt * v(n+1)        -- first order, energy-stable;
// explicit midpoint (second order) for Euler's rotation equations in the body frame,
//   I dw/dt = tau - w x (I w),
// and the exact exponential map of the midpoint angular velocity for the orientation quaternion.
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

// Advances the body-frame angular velocity w by dt (explicit midpoint) and returns the midpoint
// angular velocity, which the orientation update uses.
DEME_HD inline float3 advanceAngularVelocity(float3& w, const float3& torqueLocal, const float3& moi, float dt) {
    const float3 invMoi = make_float3(1.f / moi.x, 1.f / moi.y, 1.f / moi.z);
    const float3 wHalf = w + (0.5f * dt) * eulerAngularAccInv(w, torqueLocal, moi, invMoi);
    w = w + dt * eulerAngularAccInv(wHalf, torqueLocal, moi, invMoi);
    return wHalf;
}

}  // namespace deme
