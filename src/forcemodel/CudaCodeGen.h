// The CUDA source compiled by NVRTC at Initialize for a custom force model on the GPU: the same
// model functor as the CPU's generated code (CodeGen.h), built on the device from the plain device
// pointers of a ForceModelParams (backend/cuda/kernels/ForceModelParams.cuh), instantiated in the
// GPU force pass (backend/cuda/kernels/ForcePassKernel.cuh) and exported as an extern "C" kernel.
#pragma once

#include <string>

#include "forcemodel/ModelLayout.h"

namespace deme {

// Name of the generated kernel; it takes the built-in force passes' arguments (kernels/Dynamics.cu).
constexpr const char* kGeneratedForceKernelSymbol = "deme_force_pass_user";
// The same pass for scenes without meshes (the triangle branch left out: kernels/ForcePassKernel.cuh).
constexpr const char* kGeneratedNoMeshForceKernelSymbol = "deme_force_pass_user_no_mesh";
// The program name NVRTC compiles the source under (and names in messages outside the user's code).
constexpr const char* kGeneratedForceKernelProgram = "deme_generated_force_model.cu";

std::string generateCudaForceModelSource(const ModelLayout& layout);

}  // namespace deme
