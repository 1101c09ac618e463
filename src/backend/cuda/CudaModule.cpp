#include "backend/cuda/CudaModule.h"

#include <deme/Error.h>

#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"

namespace deme::cuda {

CudaModule::CudaModule(const std::string& call, const std::string& image) : call_(call) {
    if (image.empty()) throwError(call, "cannot load an empty GPU image");
    // PTX must end in a NUL; std::string guarantees one after its last byte, and CUBIN carries its size.
    cudaLibrary_t library = nullptr;
    DEME_CUDA_CHECK(call.c_str(),
                    cudaLibraryLoadData(&library, image.c_str(), nullptr, nullptr, 0, nullptr, nullptr, 0));
    library_ = library;
}

CudaModule::~CudaModule() {
    // No throw from a destructor; an unload can fail only once the runtime is shutting down.
    if (library_) cudaLibraryUnload(static_cast<cudaLibrary_t>(library_));
}

CudaModule::CudaModule(CudaModule&& other) noexcept : library_(other.library_), call_(std::move(other.call_)) {
    other.library_ = nullptr;
}

CudaModule& CudaModule::operator=(CudaModule&& other) noexcept {
    if (this != &other) {
        if (library_) cudaLibraryUnload(static_cast<cudaLibrary_t>(library_));
        library_ = other.library_;
        call_ = std::move(other.call_);
        other.library_ = nullptr;
    }
    return *this;
}

CudaKernel CudaModule::kernel(const std::string& name) const {
    const std::string call = call_.empty() ? "CudaModule::kernel" : call_;
    if (!library_) throwError(call, "no GPU module is loaded");
    cudaKernel_t k = nullptr;
    const cudaError_t error = cudaLibraryGetKernel(&k, static_cast<cudaLibrary_t>(library_), name.c_str());
    if (error == cudaErrorSymbolNotFound) {
        cudaGetLastError();
        throwError(call, "the GPU module has no kernel '" + name + "' (is it declared extern \"C\"?)");
    }
    DEME_CUDA_CHECK(call.c_str(), error);
    return CudaKernel{static_cast<void*>(k), name};
}

void launchKernel(const CudaKernel& kernel, Dim3 grid, Dim3 block, size_t sharedBytes, Stream stream, void** args,
                  bool overlapPrevious) {
    if (!kernel.handle) throwError("launchKernel", "no kernel to launch");
    // A grid over no items (a scene whose last clumps were removed, say) is no work; CUDA would call
    // a zero grid an invalid argument.
    if (grid.x == 0 || grid.y == 0 || grid.z == 0) return;
    cudaLaunchConfig_t config{};
    config.gridDim = dim3(grid.x, grid.y, grid.z);
    config.blockDim = dim3(block.x, block.y, block.z);
    config.dynamicSmemBytes = sharedBytes;
    config.stream = static_cast<cudaStream_t>(stream);
    cudaLaunchAttribute overlap{};
    if (overlapPrevious) {
        overlap.id = cudaLaunchAttributeProgrammaticStreamSerialization;
        overlap.val.programmaticStreamSerializationAllowed = 1;
        config.attrs = &overlap;
        config.numAttrs = 1;
    }
    // The launch takes a cudaKernel_t cast to a function pointer (CUDA 12+). The message is built
    // only on failure: a step launches a handful of kernels, thousands of times a second.
    const cudaError_t e = cudaLaunchKernelExC(&config, static_cast<const void*>(kernel.handle), args);
    if (e != cudaSuccess) {
        const std::string call = "launching kernel '" + kernel.name + "'";
        throwCudaError(e, call.c_str(), "cudaLaunchKernelExC(&config, kernel, args)", __FILE__, __LINE__);
    }
}

}  // namespace deme::cuda
