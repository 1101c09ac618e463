// Turns a failed CUDA runtime call into deme::Error. Only for files compiled with the CUDA backend
// (it needs CUDA's header); the backend's public headers stay free of it.
#pragma once

#include <cuda_runtime_api.h>

namespace deme::cuda {

// Throws deme::Error("<call>: <file>:<line>: <expression> failed: <cudaErrorName>: <description>").
[[noreturn]] void throwCudaError(cudaError_t error, const char* call, const char* expression, const char* file,
                                 int line);

inline void checkCuda(cudaError_t error, const char* call, const char* expression, const char* file, int line) {
    if (error != cudaSuccess) throwCudaError(error, call, expression, file, line);
}

}  // namespace deme::cuda

// DEME_CUDA_CHECK("DeviceBuffer::resize", cudaMalloc(&p, n)): the call is the engine function that
// failed, for the user; the expression and file:line are for whoever reads the code.
#define DEME_CUDA_CHECK(call, expression) ::deme::cuda::checkCuda((expression), (call), #expression, __FILE__, __LINE__)
