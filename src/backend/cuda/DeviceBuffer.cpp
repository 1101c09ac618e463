#include "backend/cuda/DeviceBuffer.h"

#include <deme/Error.h>

#include <cuda_runtime_api.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <string>

#include "backend/cuda/CudaCheck.h"

namespace deme::cuda {

namespace {

std::atomic<size_t> allocatedBytes{0};
std::atomic<size_t> peakBytes{0};
// Per GPU ordinal; a node has far fewer GPUs than this.
constexpr int MAX_COUNTED_DEVICES = 64;
std::atomic<size_t> allocatedOn[MAX_COUNTED_DEVICES] = {};
std::atomic<size_t> allocatedInGroup[NUM_MEMORY_GROUPS] = {};
// Each group's bytes when the total last reached its peak: where a run's peak comes from. The
// counts change under one lock (allocations are rare beside the work between them), so that the
// groups at the peak add up to it; they are read without it.
std::mutex countMutex;
size_t inGroupAtPeak[NUM_MEMORY_GROUPS] = {};
thread_local MemoryGroup currentGroup = MemoryGroup::STEP_SCRATCH;

void countAllocation(int device, MemoryGroup group, size_t bytes) {
    const std::lock_guard<std::mutex> lock(countMutex);
    const size_t now = allocatedBytes.fetch_add(bytes) + bytes;
    if (device >= 0 && device < MAX_COUNTED_DEVICES) allocatedOn[device] += bytes;
    allocatedInGroup[(int)group] += bytes;
    if (now > peakBytes.load()) {
        peakBytes = now;
        for (int g = 0; g < NUM_MEMORY_GROUPS; g++) inGroupAtPeak[g] = allocatedInGroup[g].load();
    }
}

void countFree(int device, MemoryGroup group, size_t bytes) {
    const std::lock_guard<std::mutex> lock(countMutex);
    allocatedBytes -= bytes;
    if (device >= 0 && device < MAX_COUNTED_DEVICES) allocatedOn[device] -= bytes;
    allocatedInGroup[(int)group] -= bytes;
}

cudaStream_t toCuda(Stream s) { return static_cast<cudaStream_t>(s); }

// Makes `device` current for this thread while it lives (if it is not already), and restores the
// previous one; -1: leaves the current device as it is. No throw from the destructor.
class DeviceScope {
  public:
    explicit DeviceScope(int device) {
        if (device < 0) return;
        DEME_CUDA_CHECK("DeviceBuffer", cudaGetDevice(&previous_));
        if (previous_ == device)
            previous_ = -1;  // nothing to restore
        else
            DEME_CUDA_CHECK("DeviceBuffer", cudaSetDevice(device));
    }
    ~DeviceScope() {
        if (previous_ >= 0 && cudaSetDevice(previous_) != cudaSuccess) cudaGetLastError();
    }
    DeviceScope(const DeviceScope&) = delete;
    DeviceScope& operator=(const DeviceScope&) = delete;

  private:
    int previous_ = -1;
};

int currentDevice() {
    int d = 0;
    DEME_CUDA_CHECK("DeviceBuffer", cudaGetDevice(&d));
    return d;
}

// A fresh allocation of `bytes` on the current GPU holding the first `keepBytes` of `old`; the old
// one is freed.
void* reallocate(void* old, size_t oldCapacity, size_t bytes, size_t keepBytes, MemoryGroup group, Stream stream) {
    const char* call = "DeviceBuffer";
    void* fresh = nullptr;
    const cudaError_t error = cudaMalloc(&fresh, bytes);
    if (error == cudaErrorMemoryAllocation) {
        cudaGetLastError();
        size_t freeBytes = 0, totalBytes = 0;
        cudaMemGetInfo(&freeBytes, &totalBytes);
        throwError(call, "out of GPU memory allocating " + std::to_string(bytes) + " bytes for " +
                             memoryGroupName(group) + " (" + std::to_string(freeBytes) + " of " +
                             std::to_string(totalBytes) + " free; this process's buffers hold " +
                             std::to_string(deviceBytesAllocated()) + ", ShowMemoryStats() says where)");
    }
    DEME_CUDA_CHECK(call, error);
    const int device = currentDevice();
    countAllocation(device, group, bytes);
    const size_t keep = std::min({keepBytes, oldCapacity, bytes});
    if (old && keep > 0) {
        try {
            DEME_CUDA_CHECK(call, cudaMemcpyAsync(fresh, old, keep, cudaMemcpyDeviceToDevice, toCuda(stream)));
        } catch (...) {
            cudaFree(fresh);
            countFree(device, group, bytes);
            throw;
        }
    }
    if (old) {
        // cudaFree waits for the device, so the copy above has read `old` before it goes.
        DEME_CUDA_CHECK(call, cudaFree(old));
        countFree(device, group, oldCapacity);
    }
    return fresh;
}

}  // namespace

size_t deviceBytesAllocated() { return allocatedBytes.load(); }
size_t deviceBytesAllocatedPeak() { return peakBytes.load(); }
size_t deviceBytesAllocatedOn(int device) {
    return device >= 0 && device < MAX_COUNTED_DEVICES ? allocatedOn[device].load() : 0;
}

size_t deviceBytesInGroup(MemoryGroup g) { return allocatedInGroup[(int)g].load(); }

size_t deviceBytesInGroupAtPeak(MemoryGroup g) {
    const std::lock_guard<std::mutex> lock(countMutex);
    return inGroupAtPeak[(int)g];
}

MemoryGroupScope::MemoryGroupScope(MemoryGroup g) : previous_(currentGroup) { currentGroup = g; }
MemoryGroupScope::~MemoryGroupScope() { currentGroup = previous_; }

RawDeviceBuffer::~RawDeviceBuffer() { release(); }

RawDeviceBuffer::RawDeviceBuffer(RawDeviceBuffer&& other) noexcept
    : data_(other.data_),
      capacity_(other.capacity_),
      device_(other.device_),
      group_(other.group_),
      groupFixed_(other.groupFixed_) {
    other.data_ = nullptr;
    other.capacity_ = 0;
    other.device_ = -1;
}

RawDeviceBuffer& RawDeviceBuffer::operator=(RawDeviceBuffer&& other) noexcept {
    if (this != &other) {
        release();
        data_ = other.data_;
        capacity_ = other.capacity_;
        device_ = other.device_;
        group_ = other.group_;
        groupFixed_ = other.groupFixed_;
        other.data_ = nullptr;
        other.capacity_ = 0;
        other.device_ = -1;
    }
    return *this;
}

void RawDeviceBuffer::reserve(size_t bytes, size_t keepBytes, Stream stream) {
    if (bytes <= capacity_) return;
    const size_t grown = std::max(bytes, capacity_ + capacity_ / 2);
    DeviceScope scope(device_);
    if (!data_ && !groupFixed_) group_ = currentGroup;
    if (data_ && keepBytes == 0) {
        // Nothing to keep: the old memory goes before the new is made (made first, the two were held
        // together, 2.5 times the buffer, at a large set's installation). cudaFree waits for the
        // device, as it did after the allocation.
        DEME_CUDA_CHECK("DeviceBuffer", cudaFree(data_));
        countFree(device_, group_, capacity_);
        data_ = nullptr;
        capacity_ = 0;
    }
    data_ = reallocate(data_, capacity_, grown, keepBytes, group_, stream);
    capacity_ = grown;
    device_ = currentDevice();
}

void RawDeviceBuffer::reallocateExactly(size_t bytes, size_t keepBytes, Stream stream) {
    if (bytes == capacity_) return;
    if (bytes == 0) {
        release();
        return;
    }
    DeviceScope scope(device_);
    if (!data_ && !groupFixed_) group_ = currentGroup;
    data_ = reallocate(data_, capacity_, bytes, keepBytes, group_, stream);
    capacity_ = bytes;
    device_ = currentDevice();
}

void RawDeviceBuffer::setGroup(MemoryGroup g) {
    {
        const std::lock_guard<std::mutex> lock(countMutex);
        allocatedInGroup[(int)group_] -= capacity_;
        allocatedInGroup[(int)g] += capacity_;
    }
    group_ = g;
    groupFixed_ = true;
}

void RawDeviceBuffer::release() {
    if (data_) {
        // No throw: this runs in destructors. A failure here means the context is already gone.
        // Freed with its own GPU current (the memory may belong to another GPU than the caller's).
        int previous = -1;
        if (cudaGetDevice(&previous) != cudaSuccess) cudaGetLastError();
        const bool other = device_ >= 0 && previous >= 0 && previous != device_;
        if (other && cudaSetDevice(device_) != cudaSuccess) cudaGetLastError();
        if (cudaFree(data_) != cudaSuccess) cudaGetLastError();
        if (other && cudaSetDevice(previous) != cudaSuccess) cudaGetLastError();
        countFree(device_, group_, capacity_);
    }
    data_ = nullptr;
    capacity_ = 0;
    device_ = -1;
}

void RawDeviceBuffer::uploadAsync(size_t offsetBytes, const void* host, size_t bytes, Stream stream) {
    if (bytes == 0) return;
    DEME_CUDA_CHECK("DeviceBuffer::uploadAsync", cudaMemcpyAsync(static_cast<char*>(data_) + offsetBytes, host, bytes,
                                                                 cudaMemcpyHostToDevice, toCuda(stream)));
}

void RawDeviceBuffer::downloadAsync(size_t offsetBytes, void* host, size_t bytes, Stream stream) const {
    if (bytes == 0) return;
    DEME_CUDA_CHECK("DeviceBuffer::downloadAsync", cudaMemcpyAsync(host, static_cast<const char*>(data_) + offsetBytes,
                                                                   bytes, cudaMemcpyDeviceToHost, toCuda(stream)));
}

void RawDeviceBuffer::zeroAsync(size_t offsetBytes, size_t bytes, Stream stream) {
    if (bytes == 0) return;
    DEME_CUDA_CHECK("DeviceBuffer::zeroAsync",
                    cudaMemsetAsync(static_cast<char*>(data_) + offsetBytes, 0, bytes, toCuda(stream)));
}

void RawDeviceBuffer::copyFromAsync(size_t offsetBytes, const RawDeviceBuffer& src, size_t srcOffsetBytes,
                                    size_t bytes, Stream stream) {
    if (bytes == 0) return;
    // cudaMemcpyDefault: with unified addressing the runtime knows each pointer's GPU, and a copy
    // between two GPUs goes peer to peer where they can, through the host where they cannot.
    DEME_CUDA_CHECK("DeviceBuffer::copyFromAsync",
                    cudaMemcpyAsync(static_cast<char*>(data_) + offsetBytes,
                                    static_cast<const char*>(src.data_) + srcOffsetBytes, bytes, cudaMemcpyDefault,
                                    toCuda(stream)));
}

void synchronize(Stream stream) { DEME_CUDA_CHECK("synchronize", cudaStreamSynchronize(toCuda(stream))); }

}  // namespace deme::cuda
