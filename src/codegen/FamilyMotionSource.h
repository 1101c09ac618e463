// The families' prescribed motion as CUDA source, compiled at run time by NVRTC with the other
// kernels: the GPU evaluates the user's expressions itself every step, so no per-step table travels
// from the host. The kernel computes exactly what runtime/FamilyRules.h evaluates on the CPU.
#pragma once

#include <array>
#include <string>

#include "codegen/FamilyMotion.h"

namespace deme {

// Name of the generated kernel, launched once at the start of each GPU batch of steps
// (dynamics/StepBatch.h, backend/cuda/CudaStepBatch.cpp):
//   deme_family_motion(const StepBatchControl* ctl, FamilyStepMotion* out, unsigned int numSteps,
//                      float3* contactForce, float3* contactTorque, unsigned int numCleared)
// thread k * NUM_FAMILIES + f (k < numSteps) writes family f's entry for the end of the batch's step
// k into out[k * NUM_FAMILIES + f], at the time the batch's clock will have then (ctl->time plus k
// additions of ctl->dt, as finishBatchStep makes them, plus dt), so that every step of the batch reads
// its prescriptions from the table instead of a kernel of its own; threads 0 .. numCleared - 1 clear
// owner i's contact loads for the batch's first step where integration clears them in the later
// steps (numCleared is 0 where a kernel clears them at every step's start).
inline constexpr const char* kFamilyMotionKernel = "deme_family_motion";

std::string familyMotionKernelSource(const std::array<FamilyMotion, NUM_FAMILIES>& motions);

}  // namespace deme
