// A family's motion rules evaluated for one step: what the integrator applies to its owners.
// Plain data, shared by the CPU sweeps and GPU kernels.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

struct FamilyStepMotion {
    uint8_t fixed = 0;
    uint8_t linMask = 0, angMask = 0;  // bit i: component i prescribed
    float3 lin = make_float3(0.f), ang = make_float3(0.f);
};

}  // namespace deme
