// The CUDA backend's functions in a library built without CUDA (DEME_ENABLE_CUDA off, or no toolkit
// found): the same declarations, so callers need no #ifdef; queries answer "no GPU", everything else
// throws deme::Error saying that the backend was not built. cmake/CudaBackend.cmake compiles this
// file instead of the rest of src/backend/cuda/.
#include <deme/Error.h>

#include "backend/cuda/CudaBackends.h"
#include "backend/cuda/CudaModule.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DevicePrimitives.h"
#include "backend/cuda/NvrtcCompiler.h"

namespace deme::cuda {

namespace {
[[noreturn]] void notBuilt(const std::string& call) { throwError(call, cudaNotBuiltMessage()); }
}  // namespace

// ---- Device.h
bool cudaBackendBuilt() { return false; }
int builtMinimumArchitecture() { return 0; }
const DeviceInfo& useDevice(const std::string& call, int) { throwError(call, cudaNotBuiltMessage()); }
const DeviceQuery& queryDevices() {
    static const DeviceQuery none{{}, "the CUDA backend was not built into this library", {}};
    return none;
}

// ---- CudaBackends.h
Backends makeCudaBackends(const ModelLayout&, const Settings&, int,
                          const std::function<void(Verbosity, const std::string&)>&) {
    notBuilt("Initialize");
}

// ---- CudaModule.h
CudaModule::CudaModule(const std::string& call, const std::string&) { notBuilt(call); }
CudaModule::~CudaModule() = default;
CudaModule::CudaModule(CudaModule&& other) noexcept : library_(other.library_), call_(std::move(other.call_)) {}
CudaModule& CudaModule::operator=(CudaModule&& other) noexcept {
    call_ = std::move(other.call_);
    return *this;
}
CudaKernel CudaModule::kernel(const std::string&) const { notBuilt("CudaModule::kernel"); }
void launchKernel(const CudaKernel&, Dim3, Dim3, size_t, Stream, void**, bool) { notBuilt("launchKernel"); }

// ---- NvrtcCompiler.h
std::string nvrtcVersionString() { return "none"; }
bool nvrtcIsLoaded() { return false; }
CudaCompileResult compileCudaSource(const std::string& call, const std::string&, const std::string&,
                                    const CudaCompileOptions&, jit::KernelCache&) {
    notBuilt(call);
}

// ---- DeviceBuffer.h (nothing is ever allocated, so there is nothing to free)
size_t deviceBytesAllocated() { return 0; }
size_t deviceBytesAllocatedPeak() { return 0; }
size_t deviceBytesAllocatedOn(int) { return 0; }
size_t deviceBytesInGroup(MemoryGroup) { return 0; }
size_t deviceBytesInGroupAtPeak(MemoryGroup) { return 0; }
MemoryGroupScope::MemoryGroupScope(MemoryGroup) : previous_(MemoryGroup::STEP_SCRATCH) {}
MemoryGroupScope::~MemoryGroupScope() = default;
RawDeviceBuffer::~RawDeviceBuffer() = default;
void RawDeviceBuffer::setGroup(MemoryGroup g) { group_ = g; }
RawDeviceBuffer::RawDeviceBuffer(RawDeviceBuffer&&) noexcept {}
RawDeviceBuffer& RawDeviceBuffer::operator=(RawDeviceBuffer&&) noexcept { return *this; }
void RawDeviceBuffer::reserve(size_t bytes, size_t, Stream) {
    if (bytes > 0) notBuilt("DeviceBuffer");
}
void RawDeviceBuffer::release() {}
void RawDeviceBuffer::reallocateExactly(size_t bytes, size_t, Stream) {
    if (bytes > 0) notBuilt("DeviceBuffer");
}
void RawDeviceBuffer::uploadAsync(size_t, const void*, size_t, Stream) { notBuilt("DeviceBuffer::uploadAsync"); }
void RawDeviceBuffer::downloadAsync(size_t, void*, size_t, Stream) const { notBuilt("DeviceBuffer::downloadAsync"); }
void RawDeviceBuffer::zeroAsync(size_t, size_t, Stream) { notBuilt("DeviceBuffer::zeroAsync"); }
void RawDeviceBuffer::copyFromAsync(size_t, const RawDeviceBuffer&, size_t, size_t, Stream) {
    notBuilt("DeviceBuffer::copyFromAsync");
}
void synchronize(Stream) { notBuilt("synchronize"); }
void startProfilerCapture() {}

// ---- DevicePrimitives.h
void DevicePrimitives::sortPairs(const uint64_t*, uint64_t*, const uint32_t*, uint32_t*, size_t, Stream, int, int) {
    notBuilt("DevicePrimitives::sortPairs");
}
void DevicePrimitives::sortPairs(const uint32_t*, uint32_t*, const uint32_t*, uint32_t*, size_t, Stream, int, int) {
    notBuilt("DevicePrimitives::sortPairs");
}
void DevicePrimitives::exclusiveSum(const uint32_t*, uint32_t*, size_t, Stream) {
    notBuilt("DevicePrimitives::exclusiveSum");
}
void DevicePrimitives::exclusiveSum(const uint64_t*, uint64_t*, size_t, Stream) {
    notBuilt("DevicePrimitives::exclusiveSum");
}
void DevicePrimitives::sum(const uint32_t*, uint64_t*, size_t, Stream) { notBuilt("DevicePrimitives::sum"); }
void DevicePrimitives::reduceMax(const float*, float*, size_t, Stream) { notBuilt("DevicePrimitives::reduceMax"); }
void DevicePrimitives::reduceMax(const double*, double*, size_t, Stream) { notBuilt("DevicePrimitives::reduceMax"); }
void DevicePrimitives::reduceMin(const uint32_t*, uint32_t*, size_t, Stream) {
    notBuilt("DevicePrimitives::reduceMin");
}

}  // namespace deme::cuda
