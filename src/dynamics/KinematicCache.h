// Keeps SimState::cache in step with the owner state on the host, with the per-item functions the
// owner step uses (dynamics/OwnerStep.h): after Initialize and after host-side edits of the state.
#pragma once

#include "state/SimState.h"

namespace deme {

// Analytical components in the global frame (few; done serially).
void updateAnalyticalCache(SimState& s);

// Everything, e.g. after Initialize or a host-side change of the state.
void refreshKinematicCache(SimState& s);

}  // namespace deme
