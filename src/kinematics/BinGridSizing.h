// How large the bins of contact detection are, chosen once at Initialize.
#pragma once

#include <vector>

#include "kinematics/BinGrid.h"
#include "state/SimState.h"

namespace deme {

// Bins cover the domain. Bin edge: the user's size if given, else defaultBinSize of the spheres,
// enlarged if needed so that there are at most ~8 bins per sphere over the domain (but at least 6
// along x in a sheared cell).
BinGrid makeBinGrid(const SimState& s, double requestedSize);

// The bin edge, among twice each sphere radius (grouped), for which a detection's estimated work is
// least: bin registrations (every sphere in each bin its box may touch) plus pair tests (the square
// of the registrations per occupied bin). Spheres of one size get 2 r; a few large spheres among
// many small ones get bins of the small ones (the large ones then span many bins). 0 if no sphere.
double defaultBinSize(const std::vector<float>& radii);

}  // namespace deme
