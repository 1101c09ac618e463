// One integration step of one owner, and the cached poses of its spheres and triangles: the
// per-item code of the integration sweeps, written once over the state type (SimState on the CPU, a
// StateView of device memory on the GPU). See backend/cpu/Integration.h for the sweeps.
#pragma once

#include "dynamics/OwnerStepFlags.h"
#include "physics/CompactPosition.h"
#include "physics/RigidBody.h"
#include "state/FamilyStepMotion.h"
#include "state/OwnerCentre.h"
#include "state/OwnerTypeOf.h"

namespace deme {

// What the step found wrong with an owner (worst first).
enum class OwnerFault : uint8_t { NONE = 0, TOO_FAST, NOT_FINITE, LEFT_DOMAIN };

DEME_HD_INLINE bool insideBox(const double3& x, const double3& lo, const double3& size) {
    return x.x >= lo.x && x.y >= lo.y && x.z >= lo.z && x.x <= lo.x + size.x && x.y <= lo.y + size.y &&
           x.z <= lo.z + size.z;
}

// False for infinities and NaN (written without std::isfinite, which device code lacks).
DEME_HD_INLINE bool finiteFloat(float x) { return fabsf(x) <= 3.402823466e38f; }
DEME_HD_INLINE bool finite3(const float3& v) { return finiteFloat(v.x) && finiteFloat(v.y) && finiteFloat(v.z); }

// |v|, the square root taken only where it is not zero: on a GPU a correctly rounded square root of
// zero takes its slow path (a call), and owners at rest or not turning are common. The same value.
DEME_HD_INLINE float lengthOrZero(const float3& v) {
    const float l2 = dot(v, v);
    return l2 > 0.f ? sqrtf(l2) : 0.f;
}

DEME_HD_INLINE float3 applyMask(const float3& free, const float3& prescribed, uint8_t mask) {
    return make_float3((mask & 1) ? prescribed.x : free.x, (mask & 2) ? prescribed.y : free.y,
                       (mask & 4) ? prescribed.z : free.z);
}

inline OwnerFault faultFromFlags(uint8_t f) {
    return (f & STEP_NOT_FINITE)    ? OwnerFault::NOT_FINITE
           : (f & STEP_TOO_FAST)    ? OwnerFault::TOO_FAST
           : (f & STEP_LEFT_DOMAIN) ? OwnerFault::LEFT_DOMAIN
                                    : OwnerFault::NONE;
}

// What stays fixed over one integration sweep.
struct StepConstants {
    float3 gravity;
    float h;
    double dt;
    float maxSpeed2;  // error-out speed, squared
    DomainFrame frame;
    double3 domainSize;
    // Tracker loads per owner (state/StateFields.h), or null in a call without any.
    const float3* extraAcc;
    const float3* extraAngAcc;
    // SetDomainExitPolicy("remove"): a clump that leaves the domain is parked, not a fault (on the
    // frame's parking line).
    bool parkLeavingClumps;
};

// Under the "remove" exit policy a clump that leaves the domain is not a fault that ends the batch:
// it is parked, at rest, far beyond the domain, and the host takes the parked clumps out between
// batches (Simulation::removeParkedClumps) -- at the end of the DoDynamics call, or sooner once
// many are parked -- so that an outflow costs one host round trip per call, not one per step with
// an exit. Parked clumps lie along the first bounded axis (an exit crosses a bounded face, so there
// is one), from 1000 domain lengths out, 4 domain lengths apart: no grain or mesh reaches one, the
// contacts it had end at once (their spheres are placed there in the same step), and binning
// clamps them into a border bin. Analytical walls extend there (an infinite plane, a cylinder), so
// the force pass skips a parked clump's contacts with them (its STEP_PARKED flag,
// dynamics/ContactStep.h). A parked clump stays parked: its place is outside the domain, so
// it leaves again every step, and its flags say so until the host removes it. Its voxel code says
// it is parked (PARKED_VOXEL, state/OwnerCentre.h), so that every reader of its centre finds it on
// the line (the frame's, DomainFrame::parking, worked out once with the frame).

struct OwnerStepResult {
    float travelSinceDetection;  // negative: not counted (fixed or analytical owners)
    float speed;
    uint8_t flags;
};

// Whether owner o is at rest in a fixed family: then its step is itself (velocity 0, the same pose,
// no travel), and a step leaves it out (the active box's dormant grains, docs/active-box.md).
template <class S>
DEME_HD_INLINE bool ownerAtRest(const S& s, const FamilyStepMotion* motion, size_t o) {
    return motion[s.owners.family[o]].fixed && dot(s.owners.vel[o], s.owners.vel[o]) == 0.f &&
           dot(s.owners.angVel[o], s.owners.angVel[o]) == 0.f;
}

// What owner o's step reads besides its contact loads: every field of it that a force pass leaves
// alone. Apart from those loads, so that a GPU kernel may read it while the force pass before it
// still runs (deme_integrate_and_place, kernels/Dynamics.cu), taking these loads' round trips off
// the step's path.
struct OwnerStepInputs {
    FamilyStepMotion m;
    bool dynamic;
    float3 v0, w0;
    float4 q0;
    float3 extraAcc, extraAngAcc;
    double3 x0;
    voxelID_t voxel;
    subVoxelPos_t subX, subY, subZ;
    uint8_t type;
    float extent;
    float travel0;  // since the set in use's snapshot
    float3 moi;
    float mass;
};

template <class S>
DEME_HD_INLINE OwnerStepInputs loadOwnerStepInputs(const S& s, size_t o, const FamilyStepMotion& m,
                                                   const StepConstants& c) {
    const auto& ow = s.owners;
    OwnerStepInputs in;
    in.m = m;
    in.dynamic = s.massProps.dynamic[ow.inertia[o]] != 0 && !m.fixed;
    in.v0 = ow.vel[o];
    in.w0 = ow.angVel[o];
    in.q0 = ow.oriQ[o];
    const inertiaID_t inertia = ow.inertia[o];
    // Tracker loads: the test is the same for every owner of a call (no divergence on a GPU).
    const bool loads = c.extraAcc != nullptr;
    in.extraAcc = loads ? c.extraAcc[o] : make_float3(0.f);
    in.extraAngAcc = loads ? c.extraAngAcc[o] : make_float3(0.f);
    in.voxel = ow.voxel[o];
    in.subX = ow.subX[o];
    in.subY = ow.subY[o];
    in.subZ = ow.subZ[o];
    // The decoded position alone: a parked clump's (PARKED_VOXEL) is not read (it parks again,
    // stepOwner), and the select ownerCentre makes for it cost the CPU's sweep a tenth.
    in.x0 = decodePosition(in.voxel, in.subX, in.subY, in.subZ, c.frame);
    in.type = ownerTypeOf(s, o);
    in.extent = s.massProps.extent[inertia];
    in.travel0 = ow.travel[o];
    in.moi = s.massProps.moi[inertia];
    in.mass = s.massProps.mass[inertia];
    return in;
}

// The angular velocity of owner o's step at its end (w) and at its midpoint (wMid), owner frame,
// prescriptions and fixed families applied: stepOwner's, and again finishLargeRotation's for the
// rare owner that turns too far for the series step (the one expression, so the same floats).
struct StepSpin {
    float3 w, wMid;
};
DEME_HD_INLINE StepSpin stepSpin(const OwnerStepInputs& in, const float3& torque, float h) {
    const FamilyStepMotion& m = in.m;
    const float3 moi = in.moi;
    const float3 invMoi = make_float3(1.f / moi.x, 1.f / moi.y, 1.f / moi.z);
    const float3 torqueLocal = rotateToLocal(in.q0, torque) + in.extraAngAcc * moi;
    const AngularStep rot = advanceAngularVelocity(in.w0, torqueLocal, moi, invMoi, h);
    float3 w = in.dynamic ? rot.wEnd : in.w0;
    float3 wMid = in.dynamic ? rot.wMid : in.w0;
    // Prescribed components replace the integrated ones (kinematic owners have nothing else).
    w = applyMask(w, m.ang, m.angMask);
    wMid = applyMask(wMid, m.ang, m.angMask);
    const bool fixed = m.fixed != 0;
    return StepSpin{fixed ? make_float3(0.f) : w, fixed ? make_float3(0.f) : wMid};
}

// Advances owner o by one step and refreshes its cached pose, from its inputs (above) and the
// contact loads the force pass summed on it. Written without branches (every
// path is computed, then selected) and as a function of its own, so that the owner sweep
// vectorises: the vectoriser sees this function's locals only after inlining, whereas locals of an
// `omp simd` body proper are privatised per lane. Every field it reads is read first, before any
// store: a compiler may not move a load above a store to memory it cannot prove apart, so a load
// written after a store waits for everything the store waits for. On a GPU each such wait is a
// memory round trip in every thread's path, and at lab scale (one wave of threads) the sweep's
// time is that path.
template <class S>
DEME_HD_INLINE OwnerStepResult stepOwner(S& s, size_t o, const OwnerStepInputs& in, const float3& force,
                                         const float3& torque, const StepConstants& c) {
    auto& ow = s.owners;
    const FamilyStepMotion& m = in.m;
    const bool fixed = m.fixed != 0;
    const bool dynamic = in.dynamic;
    const float3 v0 = in.v0, w0 = in.w0;
    const float4 q0 = in.q0;
    const float3 extraAcc = in.extraAcc;
    const double3 x0 = in.x0;
    voxelID_t voxel = in.voxel;
    subVoxelPos_t subX = in.subX, subY = in.subY, subZ = in.subZ;
    const bool clump = in.type == OWNER_CLUMP, analytical = in.type == OWNER_ANALYTICAL;
    const float extent = in.extent;
    const float travel0 = in.travel0;
    const float mass = in.mass;

    // Forces and torques (discarded below for owners they do not move).
    const float3 acc = force * (1.f / mass) + c.gravity + extraAcc;
    float3 v = dynamic ? advanceVelocity(v0, acc, c.h) : v0;
    // Prescribed components replace the integrated ones (kinematic owners have nothing else).
    v = applyMask(v, m.lin, m.linMask);
    v = fixed ? make_float3(0.f) : v;
    const StepSpin spin = stepSpin(in, torque, c.h);
    float3 w = spin.w;
    const float3 wMid = spin.wMid;

    const float w2 = dot(wMid, wMid);
    const float h2 = 0.25f * w2 * c.h * c.h;
    const bool large = !(h2 < ORIENTATION_SERIES_MAX_H2);
    const float4 qStep = orientationStepSeries(q0, wMid, c.h, h2);
    const float4 q = (w2 > 0.f && !large) ? qStep : q0;

    // A fixed owner has v = 0, so x is its decoded position and re-encodes to the same code. Along a
    // periodic axis an owner that left through one face enters through the other; in a sheared cell
    // (Lees–Edwards) one that left through a z face also changes its x velocity by the shear
    // velocity, and is displaced by the offset at the step's end. A position outside the code's
    // range keeps the old code.
    float dvx;
    const double3 x = wrapIntoDomain(c.frame.periodic, advancePosition(x0, v, c.dt), c.frame.origin, c.dt, dvx);
    v.x += dvx;
    const bool encoded = encodePosition(x, c.frame, voxel, subX, subY, subZ);
    const bool notFinite = !finite3(v) || !finite3(w) || !finiteFloat(q.w);
    const bool tooFast = dynamic && dot(v, v) > c.maxSpeed2;
    const bool wasParked = (in.voxel & PARKED_VOXEL) != 0;  // (its x0 is not its place: it stays)
    const bool left = (clump && !insideBox(x, c.frame.origin, c.domainSize)) || !encoded || wasParked;
    // A diverged clump is a fault whatever the policy.
    const bool park = c.parkLeavingClumps && clump && left && !notFinite && !tooFast;
    v = park ? make_float3(0.f) : v;
    w = park ? make_float3(0.f) : w;
    OwnerStepResult r;
    r.flags = notFinite ? STEP_NOT_FINITE : tooFast ? STEP_TOO_FAST : park ? STEP_PARKED : left ? STEP_LEFT_DOMAIN : 0;
    r.flags |= (dynamic || dot(v, v) > 0.f || dot(w, w) > 0.f) ? STEP_MOVED : 0;
    const bool largeStep = large && !park;
    r.flags |= largeStep ? STEP_LARGE_ROTATION : 0;

    // Travel bounds the motion of every point of the geometry (analytical owners: see below).
    const bool travels = !fixed && !analytical && !park;
    const float speed = lengthOrZero(v) + lengthOrZero(w) * extent;
    r.speed = travels ? speed : 0.f;
    const float travel = travel0 + r.speed * c.h;
    r.travelSinceDetection = travels ? travel : -1.f;

    // The owner's new state. An owner whose rotation is too large for the series keeps its
    // orientation and angular velocity at the step's start, from which the exact step that follows
    // in the same sweep (finishLargeRotation) makes them anew: no per-owner scratch for the rare case.
    ow.angVel[o] = largeStep ? w0 : w;
    ow.oriQ[o] = q;
    ow.vel[o] = v;
    ow.voxel[o] = park ? PARKED_VOXEL : voxel;
    ow.subX[o] = subX;
    ow.subY[o] = subY;
    ow.subZ[o] = subZ;
    ow.travel[o] = travel;
    return r;
}

// Owner o's step as one call: its inputs, then its loads (the CPU's sweep; a GPU kernel whose force
// pass may still run loads the inputs first, then waits, then reads the loads).
template <class S>
DEME_HD_INLINE OwnerStepResult stepOwner(S& s, size_t o, const FamilyStepMotion& m, const StepConstants& c) {
    const OwnerStepInputs in = loadOwnerStepInputs(s, o, m, c);
    const float3 force = s.owners.contactForce[o], torque = s.owners.contactTorque[o];
    return stepOwner(s, o, in, force, torque, c);
}

// The exact orientation step of an owner that stepOwner flagged STEP_LARGE_ROTATION, from its
// inputs to that step (its orientation and angular velocity still those of the step's start) and
// the torque it read: its orientation and angular velocity at the step's end.
template <class S>
DEME_HD_INLINE void finishLargeRotation(S& s, size_t o, const OwnerStepInputs& in, const float3& torque, float h) {
    const StepSpin spin = stepSpin(in, torque, h);
    s.owners.oriQ[o] = integrateOrientation(in.q0, spin.wMid, h);
    s.owners.angVel[o] = spin.w;
}
// The same, its inputs read again after the step (the CPU's sweep of such owners).
template <class S>
DEME_HD_INLINE void finishLargeRotation(S& s, size_t o, const FamilyStepMotion& m, const StepConstants& c) {
    finishLargeRotation(s, o, loadOwnerStepInputs(s, o, m, c), s.owners.contactTorque[o], c.h);
}
// Sphere i's cached centre and arm from its owner's new pose. Most clumps are single spheres at
// their centre: no rotation needed.
template <class S>
DEME_HD_INLINE void placeSphere(S& s, size_t i) {
    auto& k = s.cache;
    const bodyID_t o = s.spheres.owner[i];
    const float3 rel = s.spheres.relPos[i];
    const bool centred = rel.x == 0.f && rel.y == 0.f && rel.z == 0.f;
    const double3 arm = centred ? make_double3(0.0, 0.0, 0.0) : rotateToGlobal(s.owners.oriQ[o], to_double3(rel));
    k.spherePos[i] = ownerCentre(s, o) + arm;
    k.sphereArm[i] = to_float3(arm);
}

template <class S>
DEME_HD_INLINE void placeTriangle(S& s, size_t t) {
    auto& k = s.cache;
    const bodyID_t o = s.triangles.owner[t];
    const float4 q = s.owners.oriQ[o];
    const double3 x = ownerCentre(s, o);
    k.triVert[3 * t + 0] = localPointToGlobal(x, q, s.triangles.v0[t]);
    k.triVert[3 * t + 1] = localPointToGlobal(x, q, s.triangles.v1[t]);
    k.triVert[3 * t + 2] = localPointToGlobal(x, q, s.triangles.v2[t]);
}

// Analytical component k's cached reference point and normal/axis from its owner's pose, and an
// upper bound on how fast any point of it moves, relative to points of the domain: translation, the
// turning of its normal/axis over the domain's extent, and the swing of its reference point about
// the owner centre. Its fields are read before it stores (see stepOwner).
template <class S>
DEME_HD_INLINE float placeAnalytical(S& s, size_t k, double domainDiagonal) {
    const bodyID_t o = s.analytical.owner[k];
    const float3 relPos = s.analytical.relPos[k], relDir = s.analytical.relDir[k];
    const float4 q = s.owners.oriQ[o];
    const double3 x = ownerCentre(s, o);
    const float3 v = s.owners.vel[o], w = s.owners.angVel[o];
    const float3 wG = rotateToGlobal(q, w);
    const float3 dir = rotateToGlobal(q, relDir);
    const float3 arm = rotateToGlobal(q, relPos);
    s.cache.analPos[k] = localPointToGlobal(x, q, relPos);
    s.cache.analDir[k] = to_double3(dir);
    return length(v) + length(cross(wG, dir)) * (float)domainDiagonal + length(cross(wG, arm));
}

}  // namespace deme
