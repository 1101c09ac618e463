// Compiles CUDA C++ at run time with NVRTC into a GPU image, cached on disk (KernelCache) by
// everything that affects it, so a program run again with the same kernels starts without compiling.
// Kernels may include the embedded sources (physics/..., deme/...) exactly as the library's own code
// does; they get no standard library (see deme/HostDevice.h for what single-source code may use).
#pragma once

#include <string>
#include <vector>

#include "jit/KernelCache.h"

namespace deme::cuda {

struct CudaCompileOptions {
    // "sm_90": CUBIN for exactly that GPU. "compute_90": PTX, which the driver compiles for any GPU of
    // that architecture or newer when loading it (and which compiles without a GPU: CI checks
    // kernels so). Empty: CUBIN for the current GPU, or PTX for the newest architecture NVRTC knows
    // when the GPU is newer than NVRTC; an error where there is no usable GPU.
    std::string architecture;
    // Macros: "NAME" or "NAME=VALUE", passed as -D.
    std::vector<std::string> defines;
    // Further NVRTC options, e.g. "--use_fast_math" or "-lineinfo" (there is no fast math by default,
    // so that GPU and CPU results compare).
    std::vector<std::string> extraOptions;
};

enum class GpuImageKind { Ptx, Cubin };

struct CudaCompileResult {
    std::string image;  // PTX text or CUBIN bytes, ready for CudaModule
    GpuImageKind kind = GpuImageKind::Ptx;
    std::string architecture;  // what it was compiled for, e.g. "compute_90"
    bool cacheHit = false;
    double compileSeconds = 0;  // wall time spent in NVRTC; 0 on a cache hit
    std::string key;            // the cache key
    std::string log;            // NVRTC's warnings, if any (empty on a cache hit)
};

// NVRTC's version, e.g. "13.0" (loads the library: backend/cuda/NvrtcLibrary.h).
std::string nvrtcVersionString();

// Whether this process has NVRTC loaded: only once the CUDA backend has compiled, or asked for its
// version (tests: a CPU run must not load it).
bool nvrtcIsLoaded();

// The options every compilation gets, before the caller's: -default-device makes functions without
// __device__ device functions; DEME_DEVICE_CODE tells shared headers they are compiled for the GPU.
inline std::vector<std::string> nvrtcBaseOptions(const std::string& architecture) {
    return {"-std=c++17", "--gpu-architecture=" + architecture, "-default-device", "-DDEME_DEVICE_CODE"};
}

// Compiles `source`. `programName` is the name NVRTC gives the source in its messages and the
// include path its quoted includes are resolved from ("backend/cuda/kernels/X.cu" for an embedded
// kernel, any name for generated code). Code spliced in from a user marks itself with
// `#line 1 "force_model"`, so that errors point into the user's text. A compile error throws
// deme::Error: "<call>: " + a short header + the first 40 lines of NVRTC's log.
// The cache key covers the source, the program name, the embedded sources' hash, NVRTC's version,
// the architecture and all options.
CudaCompileResult compileCudaSource(const std::string& call, const std::string& programName, const std::string& source,
                                    const CudaCompileOptions& options = {},
                                    jit::KernelCache& cache = jit::defaultKernelCache());

}  // namespace deme::cuda
