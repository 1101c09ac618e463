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
};

// Sums each owner's contact forces and torques (in a fixed order) into contactForce/contactTorque.
void reduceContactForces(SimState& s);

// Advances every owner by dt. `travelBaseline` holds each owner's travel when the contact set in
// use was detected; the result reports the largest travel since then.
IntegrationResult integrateOwners(SimState& s, const std::array<FamilyStepMotion, NUM_FAMILIES>& motion,
                                  const float3& gravity, double dt, float errorOutVelocity,
                                  const std::vector<double>& travelBaseline);

}  // namespace deme
