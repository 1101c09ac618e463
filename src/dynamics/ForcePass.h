// The force pass (dynamics side): evaluates the contact force model on every pair of the
// active-contact set and stores each pair's force and the torques about both owners.
#pragma once

#include "runtime/SimState.h"

namespace deme {

struct ForcePassResult {
    size_t realContacts = 0;  // pairs with overlap > 0
    size_t realSphereSphere = 0;
};

ForcePassResult computeContactForces(SimState& s, double time, double dt);

// For reduction: lists, per owner, the contacts it takes part in (rebuilt after each detection).
void buildOwnerContactIndex(SimState& s);

}  // namespace deme
