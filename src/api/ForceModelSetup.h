// The force model against the user's scene: the layout the engine runs it with, checked, and the
// material tables it reads.
#pragma once

#include "api/Scene.h"
#include "forcemodel/ModelLayout.h"
#include "state/SimState.h"

namespace deme {

// Checks the scene's materials against the model (every must-have property in every material, a
// value for every pair of each pairwise property, no pair value the model does not read per pair)
// and the model's names against each other; throws deme::Error naming `call` and the culprit.
ModelLayout resolveModelLayout(const DEMForceModel& model, const Scene& scene, const char* call);

// Fills `mt`: the standard and derived tables, and the model's properties by name.
void buildMaterialTables(const Scene& scene, const ModelLayout& layout, MaterialTables& mt);

}  // namespace deme
