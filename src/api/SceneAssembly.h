// Turns the user's scene description into the flat SimState (owners, mass properties, spheres,
// analytical components, material tables, wildcard arrays) for the force model's layout, validating
// what can only be checked as a whole.
#pragma once

#include "api/Scene.h"
#include "forcemodel/ModelLayout.h"
#include "state/SimState.h"

namespace deme {

// The scene's state as Initialize starts it: owners in a space-filling-curve order, their spheres,
// components and triangles. Where every clump is one sphere at its centre and `spheresMayBeOwners`,
// the spheres are their owners at once (state/SphereLayout.h); otherwise the full sphere arrays
// (UpdateClumps merges its rows into a running state that way).
SimState assembleScene(const Scene& scene, const ModelLayout& model, bool spheresMayBeOwners = true);

}  // namespace deme
