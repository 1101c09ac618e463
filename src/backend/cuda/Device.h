// Which GPUs this process can use. Safe to call anywhere: on a machine without a GPU or a driver,
// or in a library built without CUDA, the answer is "none" and why, never an exception.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace deme::cuda {

// Whether this library was built with the CUDA backend (DEME_ENABLE_CUDA).
bool cudaBackendBuilt();

struct DeviceInfo {
    int id = 0;  // the CUDA runtime's device ordinal
    std::string name;
    int major = 0, minor = 0;  // compute capability
    size_t totalMemoryBytes = 0;
    int multiprocessors = 0;
    // "sm_<major><minor>", NVRTC's name for code built for exactly this GPU.
    std::string architecture() const { return "sm_" + std::to_string(major) + std::to_string(minor); }
};

struct DeviceQuery {
    std::vector<DeviceInfo> usable;  // devices this build can run on, in ordinal order
    // Empty when `usable` is not; otherwise why not, for a user ("no CUDA driver is installed", ...).
    std::string whyNone;
    // GPUs present but not usable (e.g. older than the architecture the build targets), with why.
    std::vector<std::string> skipped;
};

// Asks the CUDA runtime once per process (the answer cannot change while it runs) and remembers it.
const DeviceQuery& queryDevices();

inline const std::vector<DeviceInfo>& usableDevices() { return queryDevices().usable; }

// The lowest compute capability (major * 10 + minor) the ahead-of-time parts were built for
// (CMAKE_CUDA_ARCHITECTURES); 0 when not built with CUDA or when the build targets "native"/"all".
int builtMinimumArchitecture();

// Makes GPU `id` (a CUDA device ordinal) current for this thread and returns its description;
// throws deme::Error naming `call` and listing the usable ones if it is not usable.
const DeviceInfo& useDevice(const std::string& call, int id);

// Starts a profiler's capture (cudaProfilerStart), for `ncu --profile-from-start off`: the step loop
// calls it at the step named by DEME_CUDA_PROFILE_FROM_STEP, so a profile can skip the warm-up.
void startProfilerCapture();

}  // namespace deme::cuda
