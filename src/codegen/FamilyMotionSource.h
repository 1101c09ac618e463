// The families' prescribed motion as CUDA source, compiled at run time by NVRTC with the other
// kernels: the GPU evaluates the user's expressions itself every step, so no per-step table travels
// from the host. The kernel computes exactly what runtime/FamilyRules.h evaluates on the CPU.
#pragma once

#include <array>
#include <string>

#include "codegen/FamilyMotion.h"

namespace deme {

// Name of the generated kernel, the first of a GPU step (dynamics/StepBatch.h):
//   deme_family_motion(StepBatchControl* ctl, FamilyStepMotion* out, float3* contactForce,
//                      float3* contactTorque, const bodyID_t* clearIds, unsigned int numCleared)
// threads 0 .. NUM_FAMILIES - 1 write every family's entry for the end of the step (time
// ctl->time + ctl->dt); threads 0 .. numCleared - 1 clear the contact loads of owners clearIds[i]
// (owner i if clearIds is null) for the step's force pass, and thread 0 stamps the force phase's
// start into the control block. Nothing once the batch has ended (ctl->stop).
inline constexpr const char* kFamilyMotionKernel = "deme_family_motion";

std::string familyMotionKernelSource(const std::array<FamilyMotion, NUM_FAMILIES>& motions);

}  // namespace deme
