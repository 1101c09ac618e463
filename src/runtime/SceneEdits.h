// Scenes that change while they run (docs/scene-changes.md): clumps inserted between DoDynamics
// calls, clumps removed (by family, or when they leave the domain), as edits of the host state that
// keep everything else as it was. Written once for both backends: the host state is edited, and the
// backend is given the whole new state before the next step (Simulation::uploadIfEdited).
//
// Ids. Internally owners stay "clumps, then analytical owners, then meshes" and each part is stored
// in its own order (a space-filling curve per inserted batch); users see ids in the order things
// were added. An insertion therefore moves the analytical and mesh owners' internal ids and the
// analytical and triangle geometry ids up; a removal compacts every array. Both maps are monotone,
// so the contact set (sorted by geometry pair) stays sorted when its ids are renamed, and the next
// detection finds each surviving pair's history by its key. User ids are never reused: a removed
// owner's (or sphere's) user id maps to SimState::REMOVED_ID.
#pragma once

#include <cstdint>
#include <vector>

#include "state/SimState.h"

namespace deme {

// Merges `part` -- new clumps only, assembled like a scene of their own (owners in their own
// order, user ids 0.., mass properties of their templates) in the same domain frame, with the same
// wildcard counts -- into `s`: the clumps after the existing ones, their spheres after the existing
// spheres, their user ids after every user id ever issued (owners and spheres alike). Owner and
// geometry wildcards of the new rows come from `part`; the contact set keeps its pairs and history.
// The kinematic cache is left for the caller to refresh. `s` holds every owner's results
// (state/SimState.h: a GPU run's host fetches them first); `part`'s, where it has none, are zero.
void insertClumps(SimState& s, const SimState& part);

struct RemovedClumps {
    size_t count = 0;
    double mass = 0.0;
};
// Removes every clump o with remove[o] != 0 (remove has one entry per owner; entries of non-clump
// owners must be 0), its spheres, their contacts, and their rows of every wildcard; adds them to
// s.numRemovedClumps and s.removedMass. The kinematic cache is left for the caller to refresh. `s`
// holds every owner's results (as for insertClumps).
RemovedClumps removeClumps(SimState& s, const std::vector<uint8_t>& remove);

// The internal id of the owner (sphere) with user id `user`: a deme::Error naming `call` if there is
// none (never issued, or removed).
bodyID_t liveOwner(const SimState& s, size_t user, const char* call);
bodyID_t liveSphere(const SimState& s, size_t user, const char* call);

}  // namespace deme
