// The CPU's contact set keeps A as runs where spheres are their owners (a scene of one-sphere
// clumps: the mixer's grains, a drum's, a large bed). The set is sorted by A, and sphere o is owner
// o's, so the force reduction's runs of each owner's contacts as A (ContactArrays::ownerAStart)
// say every pair's A: the per-pair geomA, 4 bytes a pair (24 B a sphere at six pairs per sphere),
// is let go once the set is indexed. The force pass walks the runs; whatever empties the index (an
// installation, a detection's trimming, an edit) or reads the set on the host (contact files,
// checkpoints, stress: CpuDynamics::downloadContacts) gets geomA back first
// (ContactArrays::restoreA). DEME_CONTACT_A_PER_PAIR=1 keeps geomA (tests compare the two forms).
#pragma once

#include "state/SimState.h"

namespace deme {

// Whether the state's layout lets its set keep A as runs (and the environment does not forbid it).
bool contactAAsRunsAllowed(const SimState& s);

// Lets geomA go where allowed. With `indexFresh` the index was built from geomA just now;
// otherwise every pair's A is checked against its run first (a host reader or edit may have
// changed the set). Returns false, changing nothing, where the runs do not give geomA.
bool keepContactAAsRuns(SimState& s, bool indexFresh);

}  // namespace deme
