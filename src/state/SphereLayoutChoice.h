// Which sphere layout a host state takes (state/SphereLayout.h), and the switches between the two.
// Host only.
#pragma once

#include "state/SimState.h"

namespace deme {

// DEME_FULL_SPHERE_LAYOUT=1 (or any value but 0) in the environment: every scene keeps the full
// sphere arrays and its own sphere id maps (how tests compare the layouts).
bool fullSphereLayoutForced();

// Whether the state's spheres can be their owners: every clump is one sphere at its centre, and
// sphere i is owner i's. Always false with DEME_FULL_SPHERE_LAYOUT=1 in the environment (the full
// arrays for every scene: how tests compare the two layouts).
bool spheresCanBeOwners(const SimState& s);

// Spheres as their owners where they can be (their owners, offsets, centres and arms released), the full
// arrays otherwise (expandSphereLayout). After the scene's clumps change: Initialize, UpdateClumps,
// removals, a checkpoint read.
void chooseSphereLayout(SimState& s);

// Each owner's range of spheres, [start[o], start[o + 1]), from the spheres' owners: the state's
// ownerSphereStart where spheres are not their owners (where they are, owner o's is sphere o and the
// state keeps none).
void ownerSphereRanges(const SimState& s, std::vector<uint32_t>& start);

// Each sphere's owner, as the full layout has it: where spheres are their owners the state keeps
// none (sphere i's is i: state/SphereLayout.h's sphereOwner). ownSphereOwners puts them in the state
// (for an edit that renumbers them; chooseSphereLayout lets them go again).
void sphereOwners(const SimState& s, std::vector<bodyID_t>& owner);
void ownSphereOwners(SimState& s);

// The full arrays, whatever the scene: zero offsets, and centres and arms from the cached owner
// positions (exactly what placing a centred sphere gives). Nothing if the state has them already.
void expandSphereLayout(SimState& s);

}  // namespace deme
