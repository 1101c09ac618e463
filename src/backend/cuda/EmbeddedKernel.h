// The text of an embedded kernel source (src/backend/cuda/kernels/), for compiling it with NVRTC.
// Safe to call from several threads: the dynamics and the kinematics side compile their modules each
// on their own thread.
#pragma once

#include <string>

namespace deme::cuda {

// The source embedded under `path` (e.g. "backend/cuda/kernels/Detection.cu"); throws deme::Error
// naming Initialize if this build does not embed it.
const std::string& embeddedKernelText(const std::string& path);

}  // namespace deme::cuda
