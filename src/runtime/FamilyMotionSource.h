// The families' prescribed motion as CUDA source, compiled at run time by NVRTC with the other
// kernels: the GPU evaluates the user's expressions itself every step, so no per-step table travels
// from the host. The kernel computes exactly what FamilyRules::evaluate computes on the CPU.
#pragma once

#include <string>

#include "runtime/FamilyRules.h"

namespace deme {

// Name of the generated kernel: deme_family_motion(double t, FamilyStepMotion* out), one thread per
// family (NUM_FAMILIES threads), writing every family's entry.
inline constexpr const char* kFamilyMotionKernel = "deme_family_motion";

std::string familyMotionKernelSource(const FamilyRules& rules);

}  // namespace deme
