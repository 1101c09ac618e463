// A family's prescribed motion as the user gave it (DEMSolver::SetFamilyFixed,
// SetFamilyPrescribedLinVel / AngVel): expressions of the simulation time t per component. The CPU
// evaluates them each step (runtime/FamilyRules.h); the GPU runs them compiled
// (codegen/FamilyMotionSource.h).
#pragma once

#include <deme/VariableTypes.h>

#include "codegen/Expression.h"

namespace deme {

struct FamilyMotion {
    bool fixed = false;
    bool linPrescribed[3] = {false, false, false};
    bool angPrescribed[3] = {false, false, false};
    Expression lin[3], ang[3];
    bool hasAny() const {
        return fixed || linPrescribed[0] || linPrescribed[1] || linPrescribed[2] || angPrescribed[0] ||
               angPrescribed[1] || angPrescribed[2];
    }
};

}  // namespace deme
