// The family conditions (DEMSolver::ChangeFamilyWhen) as CUDA source, compiled at run time by
// NVRTC: the GPU checks every owner against the user's conditions itself, in one kernel, so owner
// states never travel to the host for it. The kernel does per owner exactly what
// backend/cpu/FamilyChanges.cpp does on the CPU (dynamics/FamilyChangeRule.h).
#pragma once

#include <string>
#include <vector>

#include "codegen/FamilyCondition.h"

namespace deme {

// deme_family_conditions(StateView s, unsigned int numOwners, double t, unsigned int* changed):
// one thread per owner; *changed is increased by the number of owners that changed family.
inline constexpr const char* kFamilyConditionKernel = "deme_family_conditions";

std::string familyConditionKernelSource(const std::vector<FamilyCondition>& conditions);

}  // namespace deme
