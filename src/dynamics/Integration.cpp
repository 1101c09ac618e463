#include "dynamics/Integration.h"

#include <algorithm>
#include <cmath>

#include "backend/cpu/Parallel.h"
#include "dynamics/KinematicCache.h"
#include "physics/RigidBody.h"

namespace deme {

namespace {

inline bool insideBox(const double3& x, const double3& lo, const double3& size) {
    return x.x >= lo.x && x.y >= lo.y && x.z >= lo.z && x.x <= lo.x + size.x && x.y <= lo.y + size.y &&
           x.z <= lo.z + size.z;
}

inline bool finite3(const float3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline float3 applyMask(const float3& free, const float3& prescribed, uint8_t mask) {
    return make_float3((mask & 1) ? prescribed.x : free.x, (mask & 2) ? prescribed.y : free.y,
                       (mask & 4) ? prescribed.z : free.z);
}

// Upper bound on how fast any point of an analytical component moves, relative to points of the
// domain: translation, the turning of its normal/axis over the domain's extent, and the swing of its
// reference point about the owner centre.
inline float analyticalSurfaceSpeed(const SimState& s, size_t k, double domainDiagonal) {
    const bodyID_t o = s.analytical.owner[k];
    const float4 q = s.owners.oriQ[o];
    const float3 wG = rotateToGlobal(q, s.owners.angVel[o]);
    const float3 dir = rotateToGlobal(q, s.analytical.relDir[k]);
    const float3 arm = rotateToGlobal(q, s.analytical.relPos[k]);
    return length(s.owners.vel[o]) + length(cross(wG, dir)) * (float)domainDiagonal + length(cross(wG, arm));
}

}  // namespace

void reduceContactForces(SimState& s) {
    OwnerArrays& ow = s.owners;
    const ContactArrays& c = s.contacts;
    const size_t n = ow.size();
#pragma omp parallel for schedule(static) if (n > PARALLEL_MIN_ITEMS)
    for (size_t o = 0; o < n; o++) {
        float3 F = make_float3(0.f), tau = make_float3(0.f);
        for (uint32_t e = c.ownerStart[o]; e < c.ownerStart[o + 1]; e++) {
            const uint32_t entry = c.ownerEntries[e];
            const size_t ci = entry >> 1;
            if (entry & 1u) {
                F -= c.force[ci];
                tau += c.torqueB[ci];
            } else {
                F += c.force[ci];
                tau += c.torqueA[ci];
            }
        }
        ow.contactForce[o] = F;
        ow.contactTorque[o] = tau;
    }
}

namespace {

// Bits of IntegrationScratch::flags.
enum OwnerStepFlag : uint8_t {
    STEP_NOT_FINITE = 1,
    STEP_TOO_FAST = 2,
    STEP_LEFT_DOMAIN = 4,
    STEP_LARGE_ROTATION = 8,  // orientation still to be advanced by the exact (scalar) step
    STEP_MOVED = 16,          // its geometry may have moved: cached vertices need refreshing
};
constexpr uint8_t STEP_FAULTS = STEP_NOT_FINITE | STEP_TOO_FAST | STEP_LEFT_DOMAIN;

OwnerFault faultFromFlags(uint8_t f) {
    return (f & STEP_NOT_FINITE) ? OwnerFault::NOT_FINITE
           : (f & STEP_TOO_FAST) ? OwnerFault::TOO_FAST
           : (f & STEP_LEFT_DOMAIN) ? OwnerFault::LEFT_DOMAIN
                                    : OwnerFault::NONE;
}

// What stays fixed over one integration sweep.
struct StepConstants {
    float3 gravity;
    float h;
    double dt;
    float maxSpeed2;  // error-out speed, squared
    bool trackerLoads;
    DomainFrame frame;
    double3 domainSize;
};

struct OwnerStepResult {
    double travelSinceDetection;  // negative: not counted (fixed or analytical owners)
    float speed;
    uint8_t flags;
};

// encodePosition without branches: always computes a candidate, and says whether it is valid.
DEME_HD_INLINE bool encodePositionSelect(const double3& p, const DomainFrame& f, voxelID_t& voxel, subVoxelPos_t& sx,
                                         subVoxelPos_t& sy, subVoxelPos_t& sz) {
    const double inv = 1.0 / f.subStep;
    double g[3] = {(p.x - f.origin.x) * inv + 0.5, (p.y - f.origin.y) * inv + 0.5, (p.z - f.origin.z) * inv + 0.5};
    // The negated comparisons also reject NaN.
    const bool ok = g[0] >= 0.0 && g[1] >= 0.0 && g[2] >= 0.0 && g[0] <= (double)MAX_GRID_COORD &&
                    g[1] <= (double)MAX_GRID_COORD && g[2] <= (double)MAX_GRID_COORD;
    int64_t i[3];
    for (int a = 0; a < 3; a++) i[a] = ok ? (int64_t)g[a] : 0;  // no out-of-range conversion
    const voxelID_t vNew =
        packVoxel((uint64_t)i[0] >> SUBVOXEL_BITS, (uint64_t)i[1] >> SUBVOXEL_BITS, (uint64_t)i[2] >> SUBVOXEL_BITS);
    voxel = ok ? vNew : voxel;
    sx = ok ? (subVoxelPos_t)(i[0] & 0xFFFF) : sx;
    sy = ok ? (subVoxelPos_t)(i[1] & 0xFFFF) : sy;
    sz = ok ? (subVoxelPos_t)(i[2] & 0xFFFF) : sz;
    return ok;
}

// Advances owner o by one step and refreshes its cached pose. Written without branches (every
// path is computed, then selected) and as a function of its own, so that the owner sweep
// vectorises: the vectoriser sees this function's locals only after inlining, whereas locals of an
// `omp simd` body proper are privatised per lane.
DEME_HD_INLINE OwnerStepResult stepOwner(SimState& s, size_t o, const FamilyStepMotion& m, const StepConstants& c,
                                         double travelBaseline) {
    OwnerArrays& ow = s.owners;
    KinematicCache& k = s.cache;
    const bool fixed = m.fixed != 0;
    const bool dynamic = ow.dynamic[o] != 0 && !fixed;
    const float3 v0 = ow.vel[o], w0 = ow.angVel[o];
    const float4 q0 = ow.oriQ[o];

    // Forces and torques (discarded below for owners they do not move).
    const inertiaID_t in = ow.inertia[o];
    const float3 moi = s.massProps.moi[in];
    const float3 invMoi = make_float3(1.f / moi.x, 1.f / moi.y, 1.f / moi.z);
    // Tracker loads are zero unless set, and read unconditionally: a conditional load is control flow.
    const float3 acc = ow.contactForce[o] * (1.f / s.massProps.mass[in]) + c.gravity + ow.extraAcc[o];
    const float3 torqueLocal = rotateToLocal(q0, ow.contactTorque[o]) + ow.extraAngAcc[o] * moi;
    // advanceAngularVelocity (explicit midpoint), written with values.
    const float3 wHalf = w0 + (0.5f * c.h) * eulerAngularAccInv(w0, torqueLocal, moi, invMoi);
    const float3 wEnd = w0 + c.h * eulerAngularAccInv(wHalf, torqueLocal, moi, invMoi);
    float3 v = dynamic ? v0 + c.h * acc : v0;
    float3 w = dynamic ? wEnd : w0;
    float3 wMid = dynamic ? wHalf : w0;
    // Prescribed components replace the integrated ones (kinematic owners have nothing else).
    v = applyMask(v, m.lin, m.linMask);
    w = applyMask(w, m.ang, m.angMask);
    wMid = applyMask(wMid, m.ang, m.angMask);
    v = fixed ? make_float3(0.f) : v;
    w = fixed ? make_float3(0.f) : w;
    wMid = fixed ? make_float3(0.f) : wMid;

    const float w2 = dot(wMid, wMid);
    const float h2 = 0.25f * w2 * c.h * c.h;
    const bool large = !(h2 < ORIENTATION_SERIES_MAX_H2);
    const float4 qStep = orientationStepSeries(q0, wMid, c.h, h2);
    const float4 q = (w2 > 0.f && !large) ? qStep : q0;
    s.integrationScratch.midAngVel[o] = wMid;
    ow.vel[o] = v;
    ow.angVel[o] = w;
    ow.oriQ[o] = q;

    // A fixed owner has v = 0, so x is its cached position and re-encodes to the same code.
    const double3 x = k.ownerPos[o] + to_double3(v) * c.dt;
    const bool encoded = encodePositionSelect(x, c.frame, ow.voxel[o], ow.subX[o], ow.subY[o], ow.subZ[o]);
    k.ownerPos[o] = decodePosition(ow.voxel[o], ow.subX[o], ow.subY[o], ow.subZ[o], c.frame);
    const bool notFinite = !finite3(v) || !finite3(w) || !std::isfinite(q.w);
    const bool tooFast = dynamic && dot(v, v) > c.maxSpeed2;
    const bool left = (ow.type[o] == OWNER_CLUMP && !insideBox(x, c.frame.origin, c.domainSize)) || !encoded;
    OwnerStepResult r;
    r.flags = notFinite ? STEP_NOT_FINITE : tooFast ? STEP_TOO_FAST : left ? STEP_LEFT_DOMAIN : 0;
    r.flags |= (dynamic || dot(v, v) > 0.f || dot(w, w) > 0.f) ? STEP_MOVED : 0;
    r.flags |= large ? STEP_LARGE_ROTATION : 0;

    // Travel bounds the motion of every point of the geometry (analytical owners: see below).
    const bool travels = !fixed && ow.type[o] != OWNER_ANALYTICAL;
    const float speed = length(v) + length(w) * ow.extent[o];
    r.speed = travels ? speed : 0.f;
    const double travel = ow.travel[o] + (double)(r.speed * c.h);
    ow.travel[o] = travel;
    r.travelSinceDetection = travels ? travel - travelBaseline : -1.0;
    k.ownerAngVelGlobal[o] = rotateToGlobal(q, w);
    return r;
}

// Sphere i's cached centre and arm from its owner's new pose. Most clumps are single spheres at
// their centre: no rotation needed.
DEME_HD_INLINE void placeSphere(SimState& s, size_t i) {
    KinematicCache& k = s.cache;
    const bodyID_t o = s.spheres.owner[i];
    const float3 rel = s.spheres.relPos[i];
    const bool centred = rel.x == 0.f && rel.y == 0.f && rel.z == 0.f;
    const double3 arm = centred ? make_double3(0.0, 0.0, 0.0) : rotateToGlobal(s.owners.oriQ[o], to_double3(rel));
    k.spherePos[i] = k.ownerPos[o] + arm;
    k.sphereArm[i] = to_float3(arm);
}

DEME_HD_INLINE void placeTriangle(SimState& s, size_t t) {
    KinematicCache& k = s.cache;
    const bodyID_t o = s.triangles.owner[t];
    const float4 q = s.owners.oriQ[o];
    k.triVert[3 * t + 0] = localPointToGlobal(k.ownerPos[o], q, s.triangles.v0[t]);
    k.triVert[3 * t + 1] = localPointToGlobal(k.ownerPos[o], q, s.triangles.v1[t]);
    k.triVert[3 * t + 2] = localPointToGlobal(k.ownerPos[o], q, s.triangles.v2[t]);
}

}  // namespace

// Written as sweeps without calls so that the compiler vectorises them (the owner sweep is most of
// the step's non-contact time): faults and rare large rotations are flagged per owner and handled
// afterwards.
IntegrationResult integrateOwners(SimState& s, const std::array<FamilyStepMotion, NUM_FAMILIES>& motion,
                                  const float3& gravity, double dt, float errorOutVelocity,
                                  const std::vector<double>& travelBaseline) {
    OwnerArrays& ow = s.owners;
    const size_t n = ow.size();
    const size_t nSpheres = s.spheres.size();
    const size_t nTris = s.triangles.size();
    const float h = (float)dt;
    const StepConstants consts{gravity,          (float)dt,          dt, errorOutVelocity * errorOutVelocity,
                               s.hasTrackerLoads, s.frame, s.domainSize};
    IntegrationScratch& scratch = s.integrationScratch;
    scratch.flags.resize(n);
    scratch.midAngVel.resize(n);
    uint8_t* flags = scratch.flags.data();
    const double* baseline = travelBaseline.data();
    const FamilyStepMotion* familyMotion = motion.data();
    double maxTravel = 0.0;
    float maxSpeed = 0.f;
    size_t firstFault = n;
    int anyLarge = 0;

#pragma omp parallel if (n > PARALLEL_MIN_ITEMS)
    {
#pragma omp for simd schedule(static) reduction(max : maxTravel, maxSpeed, anyLarge) reduction(min : firstFault)
        for (size_t o = 0; o < n; o++) {
            const OwnerStepResult r = stepOwner(s, o, familyMotion[ow.family[o]], consts, baseline[o]);
            flags[o] = r.flags;
            maxTravel = r.travelSinceDetection > maxTravel ? r.travelSinceDetection : maxTravel;
            maxSpeed = r.speed > maxSpeed ? r.speed : maxSpeed;
            firstFault = (r.flags & STEP_FAULTS) && o < firstFault ? o : firstFault;
            anyLarge = (r.flags & STEP_LARGE_ROTATION) ? 1 : anyLarge;
        }

        // Rotations too large for the series (over 0.2 rad in one step): rare, done exactly.
        if (anyLarge) {
#pragma omp for schedule(static)
            for (size_t o = 0; o < n; o++)
                if (flags[o] & STEP_LARGE_ROTATION) {
                    ow.oriQ[o] = integrateOrientation(ow.oriQ[o], scratch.midAngVel[o], h);
                    s.cache.ownerAngVelGlobal[o] = rotateToGlobal(ow.oriQ[o], ow.angVel[o]);
                }
        }

#pragma omp for simd schedule(static)
        for (size_t i = 0; i < nSpheres; i++) placeSphere(s, i);

        // Triangle vertices of meshes that moved.
#pragma omp for schedule(static)
        for (size_t t = 0; t < nTris; t++)
            if (flags[s.triangles.owner[t]] & STEP_MOVED) placeTriangle(s, t);
    }
    const size_t faultOwner = firstFault;
    const OwnerFault fault = firstFault < n ? faultFromFlags(flags[firstFault]) : OwnerFault::NONE;
    IntegrationResult res;

    // Kinematic analytical owners: few, so done serially.
    if (s.analytical.size() > 0) {
        updateAnalyticalCache(s);
        const double diag = length(s.domainSize);
        std::vector<float> rate(s.numAnalyticalOwners, 0.f);
        for (size_t k = 0; k < s.analytical.size(); k++) {
            const size_t o = s.analytical.owner[k];
            rate[o - s.numClumps] = std::max(rate[o - s.numClumps], analyticalSurfaceSpeed(s, k, diag));
        }
        for (size_t o = s.numClumps; o < s.numClumps + s.numAnalyticalOwners; o++) {
            ow.travel[o] += (double)(rate[o - s.numClumps] * h);
            maxTravel = std::max(maxTravel, ow.travel[o] - travelBaseline[o]);
            maxSpeed = std::max(maxSpeed, rate[o - s.numClumps]);
        }
    }
    res.maxTravel = maxTravel;
    res.maxSurfaceSpeed = maxSpeed;
    res.fault = fault;
    res.faultOwner = faultOwner;
    return res;
}

}  // namespace deme
