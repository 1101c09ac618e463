// The force pass (dynamics side): evaluates the contact force model on every pair of the
// active-contact set and stores each pair's force and the torques about both owners.
#pragma once

#include "backend/cpu/ForcePassResult.h"
#include "state/SimState.h"

namespace deme {

// One force pass of a given model. The built-in models' passes are compiled into the library; a
// user's model gets one compiled at run time (forcemodel/ModelLoader.h), with the same loop.
using ForcePassFunction = ForcePassResult (*)(SimState& s, double time, double dt);

ForcePassResult frictionalHertzForcePass(SimState& s, double time, double dt);
ForcePassResult frictionlessHertzForcePass(SimState& s, double time, double dt);

// For reduction: lists, per owner, the contacts it takes part in (rebuilt after each detection).
void buildOwnerContactIndex(SimState& s);

}  // namespace deme
