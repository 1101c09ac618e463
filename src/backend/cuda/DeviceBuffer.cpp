#include "backend/cuda/DeviceBuffer.h"

#include <deme/Error.h>

#include <cuda_runtime_api.h>

#include <algorithm>
#include <atomic>
#include <string>

#include "backend/cuda/CudaCheck.h"

namespace deme::cuda {

namespace {

std::atomic<size_t> allocatedBytes{0};
std::atomic<size_t> peakBytes{0};

void countAllocation(size_t bytes) {
    const size_t now = allocatedBytes.fetch_add(bytes) + bytes;
    size_t peak = peakBytes.load();
    while (now > peak && !peakBytes.compare_exchange_weak(peak, now)) {
    }
}

cudaStream_t toCuda(Stream s) { return static_cast<cudaStream_t>(s); }

// A fresh allocation of `bytes` holding the first `keepBytes` of `old`; the old one is freed.
void* reallocate(void* old, size_t oldCapacity, size_t bytes, size_t keepBytes, Stream stream) {
    const char* call = "DeviceBuffer";
    void* fresh = nullptr;
    const cudaError_t error = cudaMalloc(&fresh, bytes);
    if (error == cudaErrorMemoryAllocation) {
        cudaGetLastError();
        size_t freeBytes = 0, totalBytes = 0;
        cudaMemGetInfo(&freeBytes, &totalBytes);
        throwError(call, "out of GPU memory allocating " + std::to_string(bytes) + " bytes (" +
                             std::to_string(freeBytes) + " of " + std::to_string(totalBytes) +
                             " free; this process's buffers hold " + std::to_string(deviceBytesAllocated()) + ")");
    }
    DEME_CUDA_CHECK(call, error);
    countAllocation(bytes);
    const size_t keep = std::min({keepBytes, oldCapacity, bytes});
    if (old && keep > 0) {
        try {
            DEME_CUDA_CHECK(call, cudaMemcpyAsync(fresh, old, keep, cudaMemcpyDeviceToDevice, toCuda(stream)));
        } catch (...) {
            cudaFree(fresh);
            allocatedBytes -= bytes;
            throw;
        }
    }
    if (old) {
        // cudaFree waits for the device, so the copy above has read `old` before it goes.
        DEME_CUDA_CHECK(call, cudaFree(old));
        allocatedBytes -= oldCapacity;
    }
    return fresh;
}

}  // namespace

size_t deviceBytesAllocated() { return allocatedBytes.load(); }
size_t deviceBytesAllocatedPeak() { return peakBytes.load(); }

RawDeviceBuffer::~RawDeviceBuffer() { release(); }

RawDeviceBuffer::RawDeviceBuffer(RawDeviceBuffer&& other) noexcept : data_(other.data_), capacity_(other.capacity_) {
    other.data_ = nullptr;
    other.capacity_ = 0;
}

RawDeviceBuffer& RawDeviceBuffer::operator=(RawDeviceBuffer&& other) noexcept {
    if (this != &other) {
        release();
        data_ = other.data_;
        capacity_ = other.capacity_;
        other.data_ = nullptr;
        other.capacity_ = 0;
    }
    return *this;
}

void RawDeviceBuffer::reserve(size_t bytes, size_t keepBytes, Stream stream) {
    if (bytes <= capacity_) return;
    const size_t grown = std::max(bytes, capacity_ + capacity_ / 2);
    data_ = reallocate(data_, capacity_, grown, keepBytes, stream);
    capacity_ = grown;
}

void RawDeviceBuffer::reallocateExactly(size_t bytes, size_t keepBytes, Stream stream) {
    if (bytes == capacity_) return;
    if (bytes == 0) {
        release();
        return;
    }
    data_ = reallocate(data_, capacity_, bytes, keepBytes, stream);
    capacity_ = bytes;
}

void RawDeviceBuffer::release() {
    if (data_) {
        // No throw: this runs in destructors. A failure here means the context is already gone.
        if (cudaFree(data_) != cudaSuccess) cudaGetLastError();
        allocatedBytes -= capacity_;
    }
    data_ = nullptr;
    capacity_ = 0;
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

void synchronize(Stream stream) { DEME_CUDA_CHECK("synchronize", cudaStreamSynchronize(toCuda(stream))); }

}  // namespace deme::cuda
