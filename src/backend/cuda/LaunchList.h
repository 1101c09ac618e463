// A recorded sequence of kernel launches, with copies of their arguments:
// what one step of the dynamics side queues, written down first so that it can be queued directly or
// captured once into a CUDA graph and replayed (StepGraph.h), and compared with the sequence a
// graph was made from (two lists are the same when every kernel, shape and argument byte is, and
// both overlap their launches or neither does).
#pragma once

#include <cstddef>
#include <cstring>
#include <type_traits>
#include <vector>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/CudaTypes.h"

namespace deme::cuda {

class LaunchList {
  public:
    void clear() {
        m_items.clear();
        m_args.clear();
        m_bytes.clear();
    }
    bool empty() const { return m_items.empty(); }
    // Each kernel of the list may start while the one before it drains (programmatic dependent
    // launch, kernels/DependentLaunch.cuh): every kernel in the list must then begin with
    // beginDependentKernel(). Kept by clear().
    void overlapLaunches(bool on) { m_overlap = on; }
    bool overlapsLaunches() const { return m_overlap; }
    size_t size() const { return m_items.size(); }

    // kernel(args...) on `grid` blocks of `block` threads, as launch() in CudaModule.h takes it
    // (arguments of exactly the kernel parameters' types). A grid of no blocks is no work and is
    // left out, as launch() leaves it out.
    template <class... Args>
    void kernel(const CudaKernel& k, Dim3 grid, Dim3 block, size_t sharedBytes, const Args&... args) {
        static_assert((std::is_trivially_copyable_v<Args> && ...), "kernel arguments are copied by their bytes");
        if (grid.x == 0 || grid.y == 0 || grid.z == 0) return;
        Item it;
        it.kernel = &k;
        it.handle = k.handle;
        it.grid = grid;
        it.block = block;
        it.sharedBytes = sharedBytes;
        it.firstArg = m_args.size();
        (addArg(&args, sizeof(Args)), ...);
        it.numArgs = m_args.size() - it.firstArg;
        m_items.push_back(it);
    }
    // Queues the sequence on `stream` (also while the stream is being captured into a graph).
    // Throws deme::Error naming the kernel if a launch is refused.
    void enqueue(Stream stream) const;

    // The same kernels in the same order, with the same shapes and argument bytes.
    bool operator==(const LaunchList& o) const {
        if (m_overlap != o.m_overlap || m_items.size() != o.m_items.size() || m_args.size() != o.m_args.size() ||
            m_bytes != o.m_bytes)
            return false;
        for (size_t i = 0; i < m_items.size(); i++) {
            const Item &a = m_items[i], &b = o.m_items[i];
            if (a.handle != b.handle || !same(a.grid, b.grid) || !same(a.block, b.block) ||
                a.sharedBytes != b.sharedBytes || a.firstArg != b.firstArg || a.numArgs != b.numArgs)
                return false;
        }
        for (size_t a = 0; a < m_args.size(); a++)
            if (m_args[a].offset != o.m_args[a].offset || m_args[a].size != o.m_args[a].size) return false;
        return true;
    }
    bool operator!=(const LaunchList& o) const { return !(*this == o); }

  private:
    static bool same(const Dim3& a, const Dim3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
    struct Item {
        const CudaKernel* kernel = nullptr;  // for its name in messages
        void* handle = nullptr;              // the kernel launched (compared: a kernel may be recompiled)
        Dim3 grid, block;
        size_t sharedBytes = 0;
        size_t firstArg = 0, numArgs = 0;
    };
    struct Arg {
        size_t offset, size;
    };
    // Arguments at 16-byte aligned offsets of one byte array (no kernel argument needs more).
    void addArg(const void* p, size_t size) {
        const size_t offset = (m_bytes.size() + 15) & ~size_t(15);
        m_bytes.resize(offset + size, 0);
        std::memcpy(m_bytes.data() + offset, p, size);
        m_args.push_back(Arg{offset, size});
    }

    std::vector<Item> m_items;
    std::vector<Arg> m_args;
    std::vector<unsigned char> m_bytes;
    bool m_overlap = false;
};

}  // namespace deme::cuda
