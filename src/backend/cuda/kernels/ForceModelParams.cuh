// What a force-pass kernel's model reads besides the state: device pointers to the material tables
// and to the owner and geometry wildcards, each kind flat in one array (one row per property or
// wildcard, in the model's order: forcemodel/ModelLayout.h). Plain data, passed by value to every
// force-pass kernel, built-in or generated, so that they all take the same arguments.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

struct ForceModelParams {
    // The standard pair tables (numMaterials x numMaterials), as MaterialTables has them.
    const float *mu, *Crr, *E_eff, *G_eff, *beta_CoR;
    const float* props;        // per-material properties: numProps rows of numMaterials
    const float* pairProps;    // per-pair properties: numPairProps rows of numMaterials^2
    float* ownerWildcards;     // numOwnerWildcards rows of numOwners
    float* geometryWildcards;  // numGeometryWildcards rows of numGeometries (unified geometry ids)
    unsigned int numMaterials, numOwners, numGeometries;
};

}  // namespace deme
