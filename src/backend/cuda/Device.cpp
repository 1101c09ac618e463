#include "backend/cuda/Device.h"

#include <deme/Error.h>

#include <cuda_profiler_api.h>
#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"

// Set by cmake/CudaBackend.cmake from CMAKE_CUDA_ARCHITECTURES.
#ifndef DEME_CUDA_MIN_ARCH
#define DEME_CUDA_MIN_ARCH 0
#endif

namespace deme::cuda {

namespace {

std::string versionText(int v) { return std::to_string(v / 1000) + "." + std::to_string((v % 1000) / 10); }

// The runtime says "CUDA driver version is insufficient" both when the driver is too old and when
// there is none at all; the driver version tells the two apart.
std::string whyNoDevice(cudaError_t error) {
    const std::string detail = std::string(" (") + cudaGetErrorName(error) + ": " + cudaGetErrorString(error) + ")";
    if (error == cudaErrorInsufficientDriver) {
        int driver = 0, runtime = 0;
        cudaDriverGetVersion(&driver);
        cudaRuntimeGetVersion(&runtime);
        if (driver == 0) return "no CUDA driver is installed (libcuda.so.1 was not found)" + detail;
        return "the CUDA driver supports CUDA " + versionText(driver) + " but this build needs " +
               versionText(runtime) + detail;
    }
    if (error == cudaErrorNoDevice) return "no CUDA-capable GPU was found" + detail;
    return "the CUDA runtime could not list the GPUs" + detail;
}

DeviceQuery runQuery() {
    DeviceQuery q;
    int count = 0;
    const cudaError_t error = cudaGetDeviceCount(&count);
    if (error != cudaSuccess) {
        cudaGetLastError();  // leave no error behind for the next, unrelated call
        q.whyNone = whyNoDevice(error);
        return q;
    }
    for (int id = 0; id < count; id++) {
        cudaDeviceProp prop{};
        if (const cudaError_t e = cudaGetDeviceProperties(&prop, id); e != cudaSuccess) {
            cudaGetLastError();
            q.skipped.push_back("GPU " + std::to_string(id) + ": cannot read its properties (" + cudaGetErrorName(e) +
                                ")");
            continue;
        }
        DeviceInfo d;
        d.id = id;
        d.name = prop.name;
        d.major = prop.major;
        d.minor = prop.minor;
        d.totalMemoryBytes = prop.totalGlobalMem;
        d.multiprocessors = prop.multiProcessorCount;
        // The ahead-of-time kernels (CUB sorts and scans) exist only for the built architectures and,
        // through their PTX, newer ones.
        if (d.major * 10 + d.minor < DEME_CUDA_MIN_ARCH) {
            q.skipped.push_back("GPU " + std::to_string(id) + " (" + d.name + ", compute capability " +
                                std::to_string(d.major) + "." + std::to_string(d.minor) +
                                ") is older than the architecture this build targets (" +
                                std::to_string(DEME_CUDA_MIN_ARCH) + ", CMAKE_CUDA_ARCHITECTURES)");
            continue;
        }
        q.usable.push_back(d);
    }
    if (q.usable.empty()) {
        q.whyNone = count == 0 ? "no CUDA-capable GPU was found" : "no GPU is usable by this build";
        for (const std::string& s : q.skipped) q.whyNone += "; " + s;
    }
    return q;
}

}  // namespace

bool cudaBackendBuilt() { return true; }

int builtMinimumArchitecture() { return DEME_CUDA_MIN_ARCH; }

const DeviceInfo& useDevice(const std::string& call, int id) {
    std::string usable;
    for (const DeviceInfo& d : usableDevices()) {
        if (d.id == id) {
            DEME_CUDA_CHECK(call.c_str(), cudaSetDevice(id));
            return d;
        }
        usable += (usable.empty() ? "" : ", ") + std::to_string(d.id) + " (" + d.name + ")";
    }
    throwError(call, "GPU " + std::to_string(id) + " is not a usable device; usable: " +
                         (usable.empty() ? std::string("none (") + queryDevices().whyNone + ")" : usable));
}

const DeviceQuery& queryDevices() {
    static const DeviceQuery query = runQuery();
    return query;
}

void throwCudaError(cudaError_t error, const char* call, const char* expression, const char* file, int line) {
    cudaGetLastError();  // a non-sticky error must not resurface at the next, unrelated check
    throwError(call, std::string(file) + ":" + std::to_string(line) + ": " + expression +
                         " failed: " + cudaGetErrorName(error) + ": " + cudaGetErrorString(error));
}

void startProfilerCapture() { DEME_CUDA_CHECK("DoDynamics", cudaProfilerStart()); }

}  // namespace deme::cuda
