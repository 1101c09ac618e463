// A compiled GPU image (PTX or CUBIN, e.g. from compileCudaSource) loaded on the GPU, and launching
// its kernels. Uses the CUDA runtime's library API (cudaLibraryLoadData, CUDA 12+), so the engine
// never links the driver library itself: the runtime finds libcuda.so.1 when it first needs it.
#pragma once

#include <string>
#include <type_traits>

#include "backend/cuda/CudaTypes.h"

namespace deme::cuda {

// A kernel of a loaded module; valid while the module lives.
struct CudaKernel {
    void* handle = nullptr;  // a cudaKernel_t
    std::string name;
};

class CudaModule {
  public:
    CudaModule() = default;
    // Loads `image` (NUL-terminated PTX text, or CUBIN bytes) into every device context, lazily.
    // Throws deme::Error naming `call` if the image cannot be loaded (no driver, an image for another
    // architecture, PTX newer than the driver...).
    CudaModule(const std::string& call, const std::string& image);
    ~CudaModule();
    CudaModule(CudaModule&& other) noexcept;
    CudaModule& operator=(CudaModule&& other) noexcept;
    CudaModule(const CudaModule&) = delete;
    CudaModule& operator=(const CudaModule&) = delete;

    bool loaded() const { return library_ != nullptr; }

    // The kernel of that name (declare kernels extern "C" so that the name is not mangled); throws
    // deme::Error naming the module's call if there is none.
    CudaKernel kernel(const std::string& name) const;

  private:
    void* library_ = nullptr;  // a cudaLibrary_t
    std::string call_;
};

// Launches with an argument array as cudaLaunchKernel takes it (one pointer per kernel parameter).
// Throws deme::Error naming the kernel if the launch is refused (the kernel's own faults show up at
// the next synchronisation). `overlapPrevious`: the kernel may start while the kernel before it on
// the stream drains; it must begin with beginDependentKernel() (kernels/DependentLaunch.cuh).
void launchKernel(const CudaKernel& kernel, Dim3 grid, Dim3 block, size_t sharedBytes, Stream stream, void** args,
                  bool overlapPrevious = false);

// launch(k, grid, block, shared, stream, a, b, c) runs k(a, b, c). The arguments must have exactly
// the kernel parameters' types (pass `unsigned int(n)`, not a size_t, to an unsigned int parameter):
// they are passed by their bytes, with no conversion.
template <class... Args>
void launch(const CudaKernel& kernel, Dim3 grid, Dim3 block, size_t sharedBytes, Stream stream, const Args&... args) {
    static_assert((std::is_trivially_copyable_v<Args> && ...), "kernel arguments are copied by their bytes");
    void* argv[] = {const_cast<void*>(static_cast<const void*>(&args))..., nullptr};
    launchKernel(kernel, grid, block, sharedBytes, stream, argv);
}

}  // namespace deme::cuda
