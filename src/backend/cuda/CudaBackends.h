// The CUDA backend's two sides, made for the GPUs the settings name (in a library built without
// CUDA, a deme::Error saying so; see CudaUnavailable.cpp).
#pragma once

#include <functional>
#include <string>

#include "forcemodel/ModelLayout.h"
#include "runtime/Backends.h"

namespace deme::cuda {

// Dynamics on the first of settings.deviceIds (else `defaultDevice`), kinematics on the second if
// given (the paper's two-GPU layout), else on the same GPU on its own stream.
Backends makeCudaBackends(const ModelLayout& model, const Settings& settings, int defaultDevice,
                          const std::function<void(Verbosity, const std::string&)>& log);

}  // namespace deme::cuda
