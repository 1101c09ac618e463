// The force pass (dynamics side): evaluates the contact force model on every pair of the
// active-contact set; A's owner takes its loads at once, each pair's force and the torque about B's
// owner are stored for the reduction.
#pragma once

#include "backend/cpu/ForcePassResult.h"
#include "state/SimState.h"

namespace deme {

// One force pass of a given model. The built-in models' passes are compiled into the library; a
// user's model gets one compiled at run time (forcemodel/ModelLoader.h), with the same loop.
using ForcePassFunction = ForcePassResult (*)(SimState& s, double time, double dt);

ForcePassResult frictionalHertzForcePass(SimState& s, double time, double dt);
ForcePassResult frictionlessHertzForcePass(SimState& s, double time, double dt);

// Per owner, the run of contacts it is A in and the list of those it is B in (rebuilt after each
// detection): how the pass and the reduction share the loads.
void buildOwnerContactIndex(SimState& s);

}  // namespace deme
