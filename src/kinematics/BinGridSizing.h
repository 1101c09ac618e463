// How large the bins of contact detection are, chosen once at Initialize.
#pragma once

#include "kinematics/BinGrid.h"
#include "state/SimState.h"

namespace deme {

// Bins cover the domain. Bin edge: the user's size if given, else twice the largest sphere radius,
// enlarged if needed so that there are at most ~8 bins per sphere.
BinGrid makeBinGrid(const SimState& s, double requestedSize);

}  // namespace deme
