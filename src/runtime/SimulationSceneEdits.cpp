// Simulation: scenes that change between and during calls (runtime/SceneEdits.h for the edits
// themselves, docs/scene-changes.md for the user's view).
#include "runtime/Simulation.h"
#include "runtime/PeriodicLimits.h"

#include <algorithm>

#include "dynamics/KinematicCache.h"
#include "dynamics/OwnerStep.h"
#include "kinematics/BinGridSizing.h"
#include "runtime/SceneEdits.h"

namespace deme {

void Simulation::insertClumps(const SimState& part) {
    checkPeriodicRadii(m_state.frame.periodic, part.spheres.radius, "UpdateClumps");
    SimState& s = editWholeState();  // the device's state first, if it has moved on
    deme::insertClumps(s, part);
    refreshKinematicCache(s);
    // New templates may bring larger spheres than the grid was sized for (uploadIfEdited gives the
    // kinematics side the new grid with the new geometry).
    m_grid = makeBinGrid(s, settings.binSize);
    log(Verbosity::INFO, "inserted " + std::to_string(part.owners.size()) + " clumps (" +
                             std::to_string(part.spheres.size()) + " spheres); now " + std::to_string(s.numClumps) +
                             " clumps");
}

size_t Simulation::removeClumps(const std::vector<uint8_t>& remove) {
    if (std::find(remove.begin(), remove.end(), 1) == remove.end()) return 0;  // no edit, no re-detection
    SimState& s = editWholeState();  // the contact set and the results are renumbered too
    const RemovedClumps r = deme::removeClumps(s, remove);
    if (r.count) refreshKinematicCache(s);
    return r.count;
}

// Clumps that left the domain under the "remove" exit policy were parked by their steps
// (dynamics/OwnerStep.h, parkingPosition), which flag them STEP_PARKED until they go: here, between
// batches, on the host. One download of the state and one upload (at the next step) for every
// clump parked since the last time, instead of one per step in which some clump leaves.
size_t Simulation::removeParkedClumps() {
    std::vector<uint8_t> flags;
    m_backends.dynamics->downloadStepFlags(flags);
    const SimState& s = state();
    std::vector<uint8_t> remove(s.owners.size(), 0);
    for (size_t o = 0; o < flags.size() && o < s.numClumps; o++) remove[o] = (flags[o] & STEP_PARKED) ? 1 : 0;
    const size_t n = removeClumps(remove);
    if (settings.verbosity >= Verbosity::STEP_METRIC)
        log(Verbosity::STEP_METRIC, "t = " + std::to_string(m_time) + " s: " + std::to_string(n) +
                                        " clumps left the domain and were removed");
    return n;
}

}  // namespace deme
