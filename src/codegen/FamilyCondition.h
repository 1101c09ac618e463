// A family change on a condition (DEMSolver::ChangeFamilyWhen): an owner of family `from` whose
// state satisfies `when` moves to family `to`. `when` is a condition (Expression::parseCondition)
// over the owner's centre of mass and velocity in the global frame and the simulation time, in the
// order of familyConditionVariables(). The CPU evaluates the parsed expression per owner
// (backend/cpu/FamilyChanges.cpp); the GPU runs it compiled (codegen/FamilyConditionSource.h).
#pragma once

#include <string>
#include <vector>

#include <deme/VariableTypes.h>

#include "codegen/Expression.h"

namespace deme {

struct FamilyCondition {
    family_t from = 0, to = 0;
    Expression when;
};

// The names a condition may use, in the order dynamics/FamilyChangeRule.h fills their values.
inline const std::vector<std::string>& familyConditionVariables() {
    static const std::vector<std::string> names{"X", "Y", "Z", "Vx", "Vy", "Vz", "t"};
    return names;
}

}  // namespace deme
