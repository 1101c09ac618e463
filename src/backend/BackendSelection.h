// Which backend runs a simulation: the CPU, or CUDA on a GPU. The user asks for "cpu", "cuda" or
// "auto" (the environment variable DEME_BACKEND, or a solver setting); "auto" takes CUDA where the
// library was built with it and a usable GPU and driver are present, and the CPU otherwise, saying
// why. Asking for "cuda" where it cannot run is an error that says why.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "backend/cuda/Device.h"
#include "runtime/Settings.h"

namespace deme {

enum class BackendRequest { Cpu, Cuda, Auto };
enum class BackendKind { Cpu, Cuda };

const char* backendName(BackendKind kind);  // "cpu" or "cuda"

// "cpu", "cuda" or "auto", in any case and with surrounding blanks ignored; anything else throws
// deme::Error naming `call` and listing the valid values.
BackendRequest parseBackendRequest(const std::string& call, const std::string& text);

// The request in $DEME_BACKEND (Auto when unset or empty); a bad value throws deme::Error.
BackendRequest backendRequestFromEnvironment();

// What the CUDA side can offer: the facts resolveBackend decides on, apart so tests can vary them.
struct CudaAvailability {
    bool built = false;                    // the library has the CUDA backend
    std::vector<cuda::DeviceInfo> usable;  // GPUs it can run on
    std::string whyNone;                   // why `usable` is empty
};

// This process's: cuda::cudaBackendBuilt() and cuda::queryDevices().
CudaAvailability currentCudaAvailability();

struct BackendChoice {
    BackendKind kind = BackendKind::Cpu;
    int deviceId = -1;   // the GPU, for CUDA (the first usable one)
    std::string reason;  // one line for the user: what was chosen and why
};

using BackendLogger = std::function<void(Verbosity, const std::string&)>;

// Decides, and reports the choice and its reason through `log` (if given) at INFO. Throws
// deme::Error (naming `call`) when CUDA is requested and cannot run.
BackendChoice resolveBackend(const std::string& call, BackendRequest requested, const CudaAvailability& cuda,
                             const BackendLogger& log = {});
// The same with this process's availability.
BackendChoice resolveBackend(const std::string& call, BackendRequest requested, const BackendLogger& log = {});

}  // namespace deme
