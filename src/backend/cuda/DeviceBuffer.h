// GPU memory owned like a std::vector: plain cudaMalloc (never managed memory, which can hang a GPU
// when oversubscribed), grown geometrically, freed with its owner. Structure-of-arrays state is sized
// once and grows when contacts grow (ARCHITECTURE.md invariant 2), so a grown buffer keeps its
// capacity: growing again to the same size costs nothing.
//
// Free of CUDA's headers (see CudaTypes.h); in a build without CUDA every allocation throws
// deme::Error saying so. Not thread-safe: one owner (thread) per buffer.
#pragma once

#include <deme/Error.h>
#include <deme/MemoryStats.h>

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "backend/cuda/CudaTypes.h"

namespace deme::cuda {

// Bytes of GPU memory held by all device buffers of this process now (on every GPU together), and at
// most so far (what GetDeviceMemUsage reports); and what they hold now on GPU `device`.
size_t deviceBytesAllocated();
size_t deviceBytesAllocatedPeak();
size_t deviceBytesAllocatedOn(int device);

// Bytes held now by the buffers of one group (MemoryGroup), all GPUs and solvers of this process.
size_t deviceBytesInGroup(MemoryGroup g);
// Bytes a group held when the total (deviceBytesAllocatedPeak) was last raised.
size_t deviceBytesInGroupAtPeak(MemoryGroup g);

// The group a buffer's memory counts to is the one current for the thread that allocates it first
// (STEP_SCRATCH outside any scope); it stays with the buffer (also when moved or swapped).
class MemoryGroupScope {
  public:
    explicit MemoryGroupScope(MemoryGroup g);
    ~MemoryGroupScope();
    MemoryGroupScope(const MemoryGroupScope&) = delete;
    MemoryGroupScope& operator=(const MemoryGroupScope&) = delete;

  private:
    MemoryGroup previous_;
};

// Untyped storage behind DeviceBuffer<T>.
class RawDeviceBuffer {
  public:
    RawDeviceBuffer() = default;
    ~RawDeviceBuffer();
    RawDeviceBuffer(RawDeviceBuffer&& other) noexcept;
    RawDeviceBuffer& operator=(RawDeviceBuffer&& other) noexcept;
    RawDeviceBuffer(const RawDeviceBuffer&) = delete;
    RawDeviceBuffer& operator=(const RawDeviceBuffer&) = delete;

    void* data() const { return data_; }
    size_t capacityBytes() const { return capacity_; }
    // The GPU holding the memory (-1 while none is held). A buffer is allocated on the GPU current
    // for the calling thread and stays on it: growing or freeing it later selects that GPU again,
    // whichever is current then (kinematics on a second GPU writes into buffers on the first).
    int device() const { return device_; }

    // Makes room for at least `bytes`: when more is needed, allocates max(bytes, 1.5 x capacity) and
    // copies the first `keepBytes` of the old contents across on `stream` (0: nothing to keep, e.g.
    // scratch space). Never shrinks.
    void reserve(size_t bytes, size_t keepBytes, Stream stream);
    // Frees everything.
    void release();
    // Counts this buffer's memory, now and later, to group g.
    void setGroup(MemoryGroup g);
    MemoryGroup group() const { return group_; }
    // Exactly `bytes` of capacity, keeping the first min(bytes, keepBytes) bytes.
    void reallocateExactly(size_t bytes, size_t keepBytes, Stream stream);

    void uploadAsync(size_t offsetBytes, const void* host, size_t bytes, Stream stream);
    void downloadAsync(size_t offsetBytes, void* host, size_t bytes, Stream stream) const;
    void zeroAsync(size_t offsetBytes, size_t bytes, Stream stream);
    // Copies `bytes` from another device buffer (same GPU, or a peer GPU: the runtime routes it) on
    // `stream`, which must belong to the GPU current for the calling thread.
    void copyFromAsync(size_t offsetBytes, const RawDeviceBuffer& src, size_t srcOffsetBytes, size_t bytes,
                       Stream stream);

  private:
    void* data_ = nullptr;
    size_t capacity_ = 0;
    int device_ = -1;
    MemoryGroup group_ = MemoryGroup::STEP_SCRATCH;  // set at the first allocation (MemoryGroupScope)
    bool groupFixed_ = false;                        // set by setGroup: scopes no longer change it
};

// Waits until everything queued on `stream` has finished; throws deme::Error if any of it failed.
void synchronize(Stream stream);

template <class T>
class DeviceBuffer {
    static_assert(std::is_trivially_copyable_v<T>, "device buffers hold plain data, copied by its bytes");

  public:
    DeviceBuffer() = default;
    explicit DeviceBuffer(size_t count, Stream stream = nullptr) { resize(count, stream); }
    // Moving hands the memory over and leaves the source empty.
    DeviceBuffer(DeviceBuffer&& other) noexcept : raw_(std::move(other.raw_)), size_(other.size_) { other.size_ = 0; }
    DeviceBuffer& operator=(DeviceBuffer&& other) noexcept {
        if (this != &other) {
            raw_ = std::move(other.raw_);
            size_ = other.size_;
            other.size_ = 0;
        }
        return *this;
    }

    T* data() { return static_cast<T*>(raw_.data()); }
    const T* data() const { return static_cast<const T*>(raw_.data()); }
    size_t size() const { return size_; }
    size_t capacity() const { return raw_.capacityBytes() / sizeof(T); }
    size_t capacityBytes() const { return raw_.capacityBytes(); }  // the memory held
    size_t bytes() const { return size_ * sizeof(T); }
    bool empty() const { return size_ == 0; }

    // Sets the size; the first min(old, new) elements keep their values, new ones are uninitialised.
    // Growth beyond the capacity reallocates to 1.5x (or what is needed); shrinking keeps the memory.
    void resize(size_t count, Stream stream = nullptr) {
        raw_.reserve(count * sizeof(T), bytes(), stream);
        size_ = count;
    }
    // Room for `count` elements without changing the size.
    void reserve(size_t count, Stream stream = nullptr) { raw_.reserve(count * sizeof(T), bytes(), stream); }
    void setGroup(MemoryGroup g) { raw_.setGroup(g); }
    MemoryGroup group() const { return raw_.group(); }
    // Gives back the memory beyond the size (the only way a buffer shrinks).
    void shrinkToFit(Stream stream = nullptr) { raw_.reallocateExactly(bytes(), bytes(), stream); }
    // Size 0 and no memory.
    void release() {
        raw_.release();
        size_ = 0;
    }

    // Copies between host and device on `stream`; the host memory must stay valid (and, for a true
    // overlap with other work, be pinned) until the stream reaches the copy.
    void uploadAsync(const T* host, size_t count, Stream stream, size_t offset = 0) {
        checkRange(offset, count);
        raw_.uploadAsync(offset * sizeof(T), host, count * sizeof(T), stream);
    }
    void downloadAsync(T* host, size_t count, Stream stream, size_t offset = 0) const {
        checkRange(offset, count);
        raw_.downloadAsync(offset * sizeof(T), host, count * sizeof(T), stream);
    }
    void zeroAsync(Stream stream) { raw_.zeroAsync(0, bytes(), stream); }
    // The first `count` elements of `src` (on this GPU or a peer) into this buffer's first ones.
    void copyFromAsync(const DeviceBuffer& src, size_t count, Stream stream) {
        checkRange(0, count);
        src.checkRange(0, count);
        raw_.copyFromAsync(0, src.raw_, 0, count * sizeof(T), stream);
    }
    // Sets the size without keeping the contents (no copy when the buffer grows): for buffers that
    // are about to be overwritten.
    void resizeDiscarding(size_t count) {
        size_ = 0;
        resize(count);
    }
    int device() const { return raw_.device(); }
    // Trades memory with a buffer of another element type; both are left with size 0 and the
    // other's capacity. For memory that serves two arrays at times when only one of them is live
    // (CudaDynamics: the idle contact set's wildcards hold the per-contact forces a step stores).
    template <class U>
    void tradeMemory(DeviceBuffer<U>& other) {
        std::swap(raw_, other.raw_);
        size_ = 0;
        other.size_ = 0;
    }

    // Whole-buffer copies that wait for the stream: for set-up, tests and output, not the step loop.
    void upload(const std::vector<T>& host, Stream stream = nullptr) {
        resize(host.size(), stream);
        uploadAsync(host.data(), host.size(), stream);
        synchronize(stream);
    }
    std::vector<T> download(Stream stream = nullptr) const {
        std::vector<T> host(size_);
        downloadAsync(host.data(), size_, stream);
        synchronize(stream);
        return host;
    }

  private:
    template <class U>
    friend class DeviceBuffer;
    void checkRange(size_t offset, size_t count) const;

    RawDeviceBuffer raw_;
    size_t size_ = 0;
};

// Sizes `d` to `h` (without keeping its contents) and queues the copy of `h` on `stream`; `h` must
// stay as it is until the stream has passed the copy.
template <class T>
void uploadResized(DeviceBuffer<T>& d, const std::vector<T>& h, Stream stream) {
    d.resizeDiscarding(h.size());
    if (!h.empty()) d.uploadAsync(h.data(), h.size(), stream);
}

template <class T>
void DeviceBuffer<T>::checkRange(size_t offset, size_t count) const {
    if (offset > size_ || count > size_ - offset)
        throwError("DeviceBuffer", "a copy of " + std::to_string(count) + " elements at " + std::to_string(offset) +
                                       " reaches beyond the buffer's " + std::to_string(size_));
}

}  // namespace deme::cuda
