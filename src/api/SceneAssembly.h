// Turns the user's scene description into the flat SimState (owners, mass properties, spheres,
// analytical components, material tables, wildcard arrays) for the force model's layout, validating
// what can only be checked as a whole.
#pragma once

#include "api/Scene.h"
#include "forcemodel/ModelLayout.h"
#include "state/SimState.h"

namespace deme {

SimState assembleScene(const Scene& scene, const ModelLayout& model);

}  // namespace deme
