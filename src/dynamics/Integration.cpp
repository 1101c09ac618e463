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

IntegrationResult integrateOwners(SimState& s, const std::array<FamilyStepMotion, NUM_FAMILIES>& motion,
                                  const float3& gravity, double dt, float errorOutVelocity,
                                  const std::vector<double>& travelBaseline) {
    OwnerArrays& ow = s.owners;
    const size_t n = ow.size();
    const float h = (float)dt;
    double maxTravel = 0.0;
    float maxSpeed = 0.f;
    IntegrationResult res;
    size_t faultOwner = n;
    OwnerFault fault = OwnerFault::NONE;

#pragma omp parallel for schedule(static) reduction(max : maxTravel, maxSpeed) if (n > PARALLEL_MIN_ITEMS)
    for (size_t o = 0; o < n; o++) {
        const float3 F = ow.contactForce[o], tau = ow.contactTorque[o];
        const FamilyStepMotion& m = motion[ow.family[o]];
        float3 v = ow.vel[o], w = ow.angVel[o];
        float3 wMid = w;
        float4 q = ow.oriQ[o];
        if (m.fixed) {
            ow.vel[o] = ow.angVel[o] = make_float3(0.f);
            s.cache.ownerAngVelGlobal[o] = make_float3(0.f);
            continue;
        }
        if (ow.dynamic[o]) {
            const float mass = s.massProps.mass[ow.inertia[o]];
            const float3 moi = s.massProps.moi[ow.inertia[o]];
            const bool loads = s.hasTrackerLoads;
            const float3 acc = F * (1.f / mass) + gravity + (loads ? ow.extraAcc[o] : make_float3(0.f));
            v = v + h * acc;
            const float3 torqueLocal = rotateToLocal(q, tau) + (loads ? ow.extraAngAcc[o] * moi : make_float3(0.f));
            wMid = advanceAngularVelocity(w, torqueLocal, moi, h);
        }
        // Prescribed components replace the integrated ones (kinematic owners have nothing else).
        v = applyMask(v, m.lin, m.linMask);
        w = applyMask(w, m.ang, m.angMask);
        wMid = applyMask(wMid, m.ang, m.angMask);

        const double3 x = s.cache.ownerPos[o] + to_double3(v) * dt;
        q = integrateOrientation(q, wMid, h);
        ow.vel[o] = v;
        ow.angVel[o] = w;
        ow.oriQ[o] = q;

        OwnerFault f = OwnerFault::NONE;
        if (!finite3(v) || !finite3(w) || !std::isfinite(q.w)) {
            f = OwnerFault::NOT_FINITE;
        } else if (ow.dynamic[o] && dot(v, v) > errorOutVelocity * errorOutVelocity) {
            f = OwnerFault::TOO_FAST;
        } else if ((ow.type[o] == OWNER_CLUMP && !insideBox(x, s.frame.origin, s.domainSize)) ||
                   !encodePosition(x, s.frame, ow.voxel[o], ow.subX[o], ow.subY[o], ow.subZ[o])) {
            f = OwnerFault::LEFT_DOMAIN;
        }
        if (f != OwnerFault::NONE) {
#pragma omp critical(deme_integration_fault)
            if (o < faultOwner) {
                faultOwner = o;
                fault = f;
            }
        }
        // An owner that cannot have moved (kinematic and at rest, e.g. a static mesh) keeps its cache.
        if (ow.dynamic[o] || dot(v, v) > 0.f || dot(w, w) > 0.f) updateOwnerCache(s, o);
        if (ow.type[o] != OWNER_ANALYTICAL) {
            const float speed = length(v) + length(w) * ow.extent[o];
            ow.travel[o] += (double)(speed * h);
            maxTravel = std::max(maxTravel, ow.travel[o] - travelBaseline[o]);
            maxSpeed = std::max(maxSpeed, speed);
        }
    }

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
