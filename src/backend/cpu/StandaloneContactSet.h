// A contact set for a state on its own, outside any solver (benchmarks and tests of the force pass):
// the kinematic cache refreshed, one detection with a given margin over the scene's own bin grid,
// every family pair resolved, and the result installed as a detection would be.
#pragma once

#include "state/SimState.h"

namespace deme {

void detectAndInstallContacts(SimState& s, double margin);

}  // namespace deme
