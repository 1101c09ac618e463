#include "backend/BackendSelection.h"

#include <deme/Error.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace deme {

namespace {

std::string trimmedLowercase(const std::string& text) {
    const size_t first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos) return "";
    const size_t last = text.find_last_not_of(" \t\r\n");
    std::string s = text.substr(first, last - first + 1);
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return (char)std::tolower(c); });
    return s;
}

std::string describe(const cuda::DeviceInfo& d) {
    return "GPU " + std::to_string(d.id) + " (" + d.name + ", " + d.architecture() + ", " +
           std::to_string(d.totalMemoryBytes >> 20) + " MiB)";
}

// Why CUDA cannot run here; empty if it can.
std::string whyNoCuda(const CudaAvailability& cuda) {
    if (!cuda.built) return "the CUDA backend was not built into this library (DEME_ENABLE_CUDA)";
    if (cuda.usable.empty())
        return "no usable GPU: " + (cuda.whyNone.empty() ? std::string("none was found") : cuda.whyNone);
    return "";
}

}  // namespace

const char* backendName(BackendKind kind) { return kind == BackendKind::Cuda ? "cuda" : "cpu"; }

BackendRequest parseBackendRequest(const std::string& call, const std::string& text) {
    const std::string s = trimmedLowercase(text);
    if (s == "cpu") return BackendRequest::Cpu;
    if (s == "cuda") return BackendRequest::Cuda;
    if (s == "auto") return BackendRequest::Auto;
    throwError(call, "unknown backend \"" + text + "\" (valid: cpu, cuda, auto)");
}

BackendRequest backendRequestFromEnvironment() {
    const char* env = std::getenv("DEME_BACKEND");
    if (!env || !*env) return BackendRequest::Auto;
    return parseBackendRequest("DEME_BACKEND", env);
}

CudaAvailability currentCudaAvailability() {
    CudaAvailability a;
    a.built = cuda::cudaBackendBuilt();
    const cuda::DeviceQuery& q = cuda::queryDevices();
    a.usable = q.usable;
    a.whyNone = q.whyNone;
    return a;
}

BackendChoice resolveBackend(const std::string& call, BackendRequest requested, const CudaAvailability& cuda,
                             const BackendLogger& log) {
    BackendChoice choice;
    const std::string whyNot = whyNoCuda(cuda);
    switch (requested) {
        case BackendRequest::Cpu:
            choice.reason = "CPU backend (requested)";
            break;
        case BackendRequest::Cuda:
            if (!whyNot.empty()) throwError(call, "the CUDA backend was requested but cannot run: " + whyNot);
            choice.kind = BackendKind::Cuda;
            choice.deviceId = cuda.usable.front().id;
            choice.reason = "CUDA backend (requested) on " + describe(cuda.usable.front());
            break;
        case BackendRequest::Auto:
            if (whyNot.empty()) {
                choice.kind = BackendKind::Cuda;
                choice.deviceId = cuda.usable.front().id;
                choice.reason = "CUDA backend (auto) on " + describe(cuda.usable.front());
            } else {
                choice.reason = "CPU backend (auto): " + whyNot;
            }
            break;
    }
    // INFO even when "auto" falls back to the CPU: a CUDA build on a machine without a GPU (CI) is
    // normal, and the reason says what to change.
    if (log) log(Verbosity::INFO, choice.reason);
    return choice;
}

BackendChoice resolveBackend(const std::string& call, BackendRequest requested, const BackendLogger& log) {
    // The CPU needs no device query (which starts the CUDA runtime).
    if (requested == BackendRequest::Cpu) return resolveBackend(call, requested, CudaAvailability{}, log);
    return resolveBackend(call, requested, currentCudaAvailability(), log);
}

}  // namespace deme
