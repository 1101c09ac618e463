// The force pass (dynamics side): evaluates the contact force model on every pair of the
// active-contact set; A's owner takes its loads at once, B's owner's are summed per block of owners
// for the reduction (backend/cpu/ForcePassLoop.h).
#pragma once

#include "backend/cpu/ForcePassResult.h"
#include "state/SimState.h"

namespace deme {

// One force pass of a given model. The built-in models' passes are compiled into the library; a
// user's model gets one compiled at run time (forcemodel/ModelLoader.h), with the same loop.
// `store`: which pairs' forces on A it keeps for readers.
using ForcePassFunction = ForcePassResult (*)(SimState& s, double time, double dt, ForceStore store);

ForcePassResult frictionalHertzForcePass(SimState& s, double time, double dt, ForceStore store);
ForcePassResult frictionlessHertzForcePass(SimState& s, double time, double dt, ForceStore store);

// Per owner, the run of contacts it is A in; per block of owners, the window of B's owners; per
// owner, its slots in the windows (rebuilt after each detection): how the pass and the reduction
// share the loads.
void buildOwnerContactIndex(SimState& s);

}  // namespace deme
