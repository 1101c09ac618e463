// The families' prescribed motion as CUDA source, compiled at run time by NVRTC with the other
// kernels: the GPU evaluates the user's expressions itself every step, so no per-step table travels
// from the host. The kernel computes exactly what runtime/FamilyRules.h evaluates on the CPU.
#pragma once

#include <array>
#include <string>

#include "codegen/FamilyMotion.h"

namespace deme {

// Name of the generated kernel: deme_family_motion(double t, FamilyStepMotion* out), one thread per
// family (NUM_FAMILIES threads), writing every family's entry.
inline constexpr const char* kFamilyMotionKernel = "deme_family_motion";

std::string familyMotionKernelSource(const std::array<FamilyMotion, NUM_FAMILIES>& motions);

}  // namespace deme
