// makeBackends (runtime/Backends.h): the backend the settings ask for, made with its force model.
#include <memory>

#include "backend/BackendSelection.h"
#include "backend/cpu/CpuDynamics.h"
#include "backend/cpu/CpuKinematics.h"
#include "backend/cuda/CudaBackends.h"
#include "runtime/Backends.h"

namespace deme {

Backends makeBackends(SimState& s, const ModelLayout& model, Settings& settings,
                      const std::function<void(Verbosity, const std::string&)>& log) {
    const BackendRequest request = settings.backend.empty() ? backendRequestFromEnvironment()
                                                            : parseBackendRequest("Initialize", settings.backend);
    const BackendChoice choice = resolveBackend("Initialize", request, log);
    settings.onGpu = choice.kind == BackendKind::Cuda;
    // Every force model runs on either: built-in ones are compiled into the library (and its GPU
    // kernels), a custom one is compiled for the backend here (host compiler or NVRTC, cached).
    if (settings.onGpu) return cuda::makeCudaBackends(model, settings, choice.deviceId, log);
    CpuForceModel cpuModel = loadCpuForceModel(model, "Initialize (contact force model)");
    const std::string how = model.builtIn()     ? "built in"
                            : cpuModel.cacheHit ? "compiled earlier, loaded from the cache"
                                                : "compiled in " + std::to_string(cpuModel.compileSeconds) + " s";
    log(Verbosity::INFO, "force model: " + model.description() + " (" + how + ")");
    auto kinematics = std::make_unique<CpuKinematics>(s, settings.kinematicsThreads);
    Backends b;
    b.dynamics = std::make_unique<CpuDynamics>(s, std::move(cpuModel), *kinematics);
    b.kinematics = std::move(kinematics);
    return b;
}

}  // namespace deme
