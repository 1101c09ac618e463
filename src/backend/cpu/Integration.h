// Force reduction onto owners and time integration (paper Eq. 5): each owner sums the forces and
// torques of its contacts, then advances its velocity, angular velocity, position and orientation.
#pragma once

#include <array>

#include "dynamics/OwnerStep.h"
#include "state/FamilyStepMotion.h"
#include "state/SimState.h"

namespace deme {

struct IntegrationResult {
    float maxTravel = 0.f;        // largest travel since the last detection, over all owners
    float maxSurfaceSpeed = 0.f;  // largest speed of any geometry point (for the next margin)
    OwnerFault fault = OwnerFault::NONE;
    size_t faultOwner = 0;  // lowest owner id with a fault
    size_t parkedOwners = 0;  // clumps parked (dynamics/OwnerStep.h, parkingPosition)
};

struct IntegrationSubset;

// Completes each owner's contact force and torque (contactForce/contactTorque): to what the force
// pass gave it as A it adds its contacts as B, in a fixed order:
// every owner, or those of subset.reduced (the others have no contacts and hold zeros).
void reduceContactForces(SimState& s, const IntegrationSubset& subset);

// Which owners and spheres a step must integrate and place: all of them, or (with dormant owners,
// the active box) those of families that are not fixed and the fixed ones not yet at rest. A fixed
// owner at rest is its own step's result (velocity 0, same pose, no travel), so it is left out.
struct IntegrationSubset {
    bool all = true;
    std::vector<bodyID_t> owners, spheres;  // ascending; used where !all
    std::vector<bodyID_t> reduced;          // owners stepped or with contacts in the set in use
    // Recomputed from the families now and their motion rules and the contact set in use (after
    // uploads, detections and the start of each call: the only times families and the set change).
    // Zeroes the contact force and torque of the owners left out of `reduced`.
    void update(SimState& s, const std::array<FamilyStepMotion, NUM_FAMILIES>& motion);
};

// Advances every owner of `subset` by dt, their travel since the contact set in use's snapshot
// (OwnerArrays::travel) too; the result reports the largest such travel.
IntegrationResult integrateOwners(SimState& s, const std::array<FamilyStepMotion, NUM_FAMILIES>& motion,
                                  const float3& gravity, double dt, float errorOutVelocity,
                                  bool parkLeavingClumps, const IntegrationSubset& subset);

}  // namespace deme
