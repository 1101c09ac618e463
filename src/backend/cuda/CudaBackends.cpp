#include "backend/cuda/CudaBackends.h"

#include <chrono>

#include "backend/cuda/CudaDynamics.h"
#include "backend/cuda/CudaKinematics.h"

namespace deme::cuda {

Backends makeCudaBackends(const ModelLayout& model, const Settings& settings, int defaultDevice,
                          const std::function<void(Verbosity, const std::string&)>& log) {
    // One GPU: dynamics and kinematics share it, each on its own stream. Two (or more; the first two
    // are used): dynamics on the first, kinematics on the second, as in the paper.
    const std::vector<int>& ids = settings.deviceIds;
    const int device = ids.empty() ? defaultDevice : ids[0];
    const int kinematicsDevice = ids.size() > 1 ? ids[1] : device;
    if (ids.size() > 2)
        log(Verbosity::WARNING, std::to_string(ids.size()) + " GPUs were given; the CUDA backend uses two (GPU " +
                                    std::to_string(device) + " for dynamics, GPU " + std::to_string(kinematicsDevice) +
                                    " for contact detection)");
    const auto t0 = std::chrono::steady_clock::now();
    auto dynamics = std::make_unique<CudaDynamics>(device, model);
    // kT starts with dT's GPU current: the exchange buffers and the event go there.
    auto kinematics = std::make_unique<CudaKinematics>(kinematicsDevice, device, dynamics->state(), dynamics->stream());
    dynamics->setKinematics(kinematics.get());
    const bool cached = dynamics->kernelsFromCache() && kinematics->kernelsFromCache();
    log(Verbosity::INFO,
        "GPU kernels for " + dynamics->deviceName() +
            (kinematicsDevice != device ? " and " + kinematics->deviceName() : std::string()) +
            (cached ? " loaded from the cache" : " compiled") + " in " +
            std::to_string(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()) +
            " s; contact detection on GPU " + std::to_string(kinematicsDevice) +
            (kinematicsDevice == device ? " (its own stream)"
             : kinematics->peerAccess() ? " (peer access to GPU " + std::to_string(device) + ")"
                                        : " (no peer access: transfers through the host)") +
            (settings.asyncDetection ? ", asynchronous" : ", synchronous"));
    log(Verbosity::INFO,
        "force model: " + model.description() + (model.builtIn() ? " (built in)" : " (compiled for the GPU by NVRTC)"));
    Backends b;
    b.dynamics = std::move(dynamics);
    b.kinematics = std::move(kinematics);
    return b;
}

}  // namespace deme::cuda
