// Sphere ids as the user numbers them (in the order spheres were added) against the state's (a
// space-filling-curve order). The usual large scene is clumps of one sphere each, added before any
// other owner: there sphere i is owner i's, and its user id is its owner's, so the state keeps no
// sphere id maps and reads the owners' (8 B a sphere less; SimState::sphereIdsAreOwnerIds). Every
// reader goes through these functions; an edit of the scene owns the maps while it runs and shares
// them again where it can (runtime/SceneEdits.cpp). Host only.
#pragma once

#include "state/SimState.h"

namespace deme {

// How many sphere user ids have been issued (removed ones included).
inline size_t userSphereCount(const SimState& s) {
    return s.sphereIdsAreOwnerIds ? s.userSphereIds : s.sphereUserToInternal.size();
}
// Sphere i's user id.
inline bodyID_t sphereUserId(const SimState& s, size_t i) {
    return s.sphereIdsAreOwnerIds ? s.ownerInternalToUser[i] : s.sphereInternalToUser[i];
}
// User sphere u's index in the state (SimState::REMOVED_ID where it was removed).
inline bodyID_t sphereInternalId(const SimState& s, size_t u) {
    return s.sphereIdsAreOwnerIds ? s.ownerUserToInternal[u] : s.sphereUserToInternal[u];
}

// The maps dropped where they equal the owners' over the spheres (not where the full sphere layout
// is forced: fullSphereLayoutForced, state/SphereLayoutChoice.h).
void shareSphereIdsWithOwners(SimState& s);
// The maps made again from the owners' (before an edit changes them). Nothing where they are kept.
void ownSphereIds(SimState& s);
// The two maps, whichever the state keeps (a checkpoint writes them).
void sphereIdMaps(const SimState& s, std::vector<bodyID_t>& internalToUser, std::vector<bodyID_t>& userToInternal);

}  // namespace deme
