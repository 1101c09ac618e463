#include "backend/cpu/Integration.h"

#include <algorithm>
#include <cmath>

#include <deme/Error.h>

#include "parallel/Parallel.h"
#include "dynamics/KinematicCache.h"
#include "dynamics/OwnerStep.h"
#include "physics/RigidBody.h"
#include "runtime/MemoryAccounting.h"
#include "state/SphereLayout.h"

namespace deme {

void reduceContactForces(SimState& s, const IntegrationSubset& subset) {
    OwnerArrays& ow = s.owners;
    const ContactArrays& c = s.contacts;
    const bodyID_t* ids = subset.all ? nullptr : subset.reduced.data();
    const size_t n = subset.all ? ow.size() : subset.reduced.size();
    if (c.ownerAStart.size() != ow.size() + 1 || c.ownerBStart.size() != ow.size() + 1)
        throwError("DoDynamics", "internal: the contact set's owner index is missing");
#pragma omp parallel for schedule(static) if (n > PARALLEL_MIN_ITEMS)
    for (size_t k = 0; k < n; k++) {
        const size_t o = ids ? (size_t)ids[k] : k;
        // What the owner took in the force pass (runForcePass: as A, and as B in its own block),
        // then as B in the other blocks: its slots in their windows, in block order. (The windows
        // hold the forces on A and minus the torques on B, so that an empty slot, +0, subtracts to
        // nothing whatever the sum's sign.)
        const bool inPass = c.ownerAStart[o + 1] > c.ownerAStart[o] || c.isBInItsBlock(o);
        float3 F = inPass ? ow.contactForce[o] : make_float3(0.f);
        float3 tau = inPass ? ow.contactTorque[o] : make_float3(0.f);
        for (uint32_t e = c.ownerBStart[o]; e < c.ownerBStart[o + 1]; e++) {
            const uint32_t w = c.ownerBSlots[e];
            F -= c.window[w].force;
            tau -= c.window[w].negTorque;
        }
        ow.contactForce[o] = F;
        ow.contactTorque[o] = tau;
    }
}

// Written as sweeps without calls so that the compiler vectorises them (the owner sweep is most of
// the step's non-contact time): faults and rare large rotations are flagged per owner and handled
// afterwards.
IntegrationResult integrateOwners(SimState& s, const std::array<FamilyStepMotion, NUM_FAMILIES>& motion,
                                  const float3& gravity, double dt, float errorOutVelocity,
                                  bool parkLeavingClumps, const IntegrationSubset& subset) {
    OwnerArrays& ow = s.owners;
    const size_t n = ow.size();
    const bodyID_t* ownerIds = subset.all ? nullptr : subset.owners.data();
    const bodyID_t* sphereIds = subset.all ? nullptr : subset.spheres.data();
    const size_t nStepped = subset.all ? n : subset.owners.size();
    // Spheres that are their owners are placed with them (state/SphereLayout.h).
    const size_t nSpheres = s.spheresAreOwners ? 0 : subset.all ? s.spheres.size() : subset.spheres.size();
    const size_t nTris = s.triangles.size();
    const float h = (float)dt;
    const TrackerLoadArrays& loads = s.trackerLoads;
    const StepConstants consts{gravity,
                               (float)dt,
                               dt,
                               errorOutVelocity * errorOutVelocity,
                               s.frame,
                               s.domainSize,
                               loads.empty() ? nullptr : loads.extraAcc.data(),
                               loads.empty() ? nullptr : loads.extraAngAcc.data(),
                               parkLeavingClumps};
    IntegrationScratch& scratch = s.integrationScratch;
    scratch.flags.resize(n);
    uint8_t* flags = scratch.flags.data();
    const FamilyStepMotion* familyMotion = motion.data();
    float maxTravel = 0.f;
    float maxSpeed = 0.f;
    size_t firstFault = n;
    size_t parked = 0;
    int anyLarge = 0;

#pragma omp parallel if (n > PARALLEL_MIN_ITEMS)
    {
#pragma omp for simd schedule(static) reduction(max : maxTravel, maxSpeed, anyLarge) reduction(min : firstFault) \
    reduction(+ : parked)
        for (size_t k = 0; k < nStepped; k++) {
            const size_t o = ownerIds ? (size_t)ownerIds[k] : k;
            const OwnerStepResult r = stepOwner(s, o, familyMotion[ow.family[o]], consts);
            flags[o] = r.flags;
            maxTravel = r.travelSinceDetection > maxTravel ? r.travelSinceDetection : maxTravel;
            maxSpeed = r.speed > maxSpeed ? r.speed : maxSpeed;
            firstFault = (r.flags & STEP_FAULTS) && o < firstFault ? o : firstFault;
            anyLarge = (r.flags & STEP_LARGE_ROTATION) ? 1 : anyLarge;
            parked += (r.flags & STEP_PARKED) ? 1 : 0;
        }

        // Rotations too large for the series (over 0.2 rad in one step): rare, done exactly.
        if (anyLarge) {
#pragma omp for schedule(static)
            for (size_t k = 0; k < nStepped; k++) {
                const size_t o = ownerIds ? (size_t)ownerIds[k] : k;
                if (flags[o] & STEP_LARGE_ROTATION) finishLargeRotation(s, o, familyMotion[ow.family[o]], consts);
            }
        }

#pragma omp for simd schedule(static)
        for (size_t k = 0; k < nSpheres; k++) placeSphere(s, sphereIds ? (size_t)sphereIds[k] : k);

            // Triangle vertices of meshes that moved.
#pragma omp for schedule(static)
        for (size_t t = 0; t < nTris; t++)
            if (flags[s.triangles.owner[t]] & STEP_MOVED) placeTriangle(s, t);
    }
    const size_t faultOwner = firstFault;
    const OwnerFault fault = firstFault < n ? faultFromFlags(flags[firstFault]) : OwnerFault::NONE;
    IntegrationResult res;

    // Kinematic analytical owners: few, so done serially; each component is placed once, by its owner.
    const double diag = length(s.domainSize);
    for (size_t o = s.numClumps; o < s.numClumps + s.numAnalyticalOwners; o++) {
        float rate = 0.f;
        for (size_t k = 0; k < s.analytical.size(); k++)
            if (s.analytical.owner[k] == o) rate = std::max(rate, placeAnalytical(s, k, diag));
        ow.travel[o] += rate * h;
        maxTravel = std::max(maxTravel, ow.travel[o]);
        maxSpeed = std::max(maxSpeed, rate);
    }
    res.maxTravel = maxTravel;
    res.maxSurfaceSpeed = maxSpeed;
    res.fault = fault;
    res.faultOwner = faultOwner;
    res.parkedOwners = parked;
    return res;
}

void IntegrationSubset::update(SimState& s, const std::array<FamilyStepMotion, NUM_FAMILIES>& motion) {
    OwnerArrays& ow = s.owners;
    const size_t n = ow.size();
    owners.clear();
    spheres.clear();
    reduced.clear();
    // Only an owner of a fixed family can be at rest: without one (most runs) no sweep is needed.
    const bool anyFixed = std::any_of(motion.begin(), motion.end(), [](const FamilyStepMotion& m) { return m.fixed; });
    std::vector<uint8_t> stepped(anyFixed ? n : 0);
    size_t count = anyFixed ? 0 : n;
    for (size_t o = 0; anyFixed && o < n; o++) {
        stepped[o] = !ownerAtRest(s, motion.data(), o);
        count += stepped[o];
    }
    all = count == n;
    if (all) {
        // Every owner steps (most runs): the lists hold nothing, and no memory either.
        releaseVector(owners);
        releaseVector(spheres);
        releaseVector(reduced);
        return;
    }
    owners.reserve(count);
    for (size_t o = 0; o < n; o++)
        if (stepped[o]) owners.push_back((bodyID_t)o);
    const std::vector<uint32_t>&a = s.contacts.ownerAStart, &b = s.contacts.ownerBStart;
    auto inContact = [&](size_t o) {
        return (a.size() > o + 1 && a[o + 1] > a[o]) || (b.size() > o + 1 && b[o + 1] > b[o]) ||
               s.contacts.isBInItsBlock(o);
    };
    for (size_t o = 0; o < n; o++) {
        if (stepped[o] || inContact(o)) {
            reduced.push_back((bodyID_t)o);
        } else {
            ow.contactForce[o] = make_float3(0.f);
            ow.contactTorque[o] = make_float3(0.f);
        }
    }
    for (size_t i = 0; i < s.spheres.size(); i++)
        if (stepped[sphereOwner(s, i)]) spheres.push_back((bodyID_t)i);
}

}  // namespace deme
