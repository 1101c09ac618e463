// A GPU contact set's As in the compact form (state/CompactPairA.h): a base per 32 pairs, a byte a
// pair and the side table of wide blocks, and what makes them: detection from its offsets, history
// mapping's merges and trim (and detection's lab-scale and dormant paths) from As written whole into
// scratch, an upload from the host's whole As; a download gives the host its As whole again.
#pragma once

#include <vector>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/DeviceBuffer.h"
#include "state/CompactPairA.h"

namespace deme::cuda {

class DevicePrimitives;

struct DevicePairA {
    DeviceBuffer<uint32_t> base;
    DeviceBuffer<uint8_t> delta;
    DeviceBuffer<bodyID_t> wide;

    PairAList view() const { return PairAList{nullptr, base.data(), delta.data(), wide.data()}; }
    PairAWriter writer() { return PairAWriter{base.data(), delta.data(), wide.data()}; }
    void setGroup(MemoryGroup g) {
        base.setGroup(g);
        delta.setGroup(g);
        wide.setGroup(g);
    }
    void release() {
        base.release();
        delta.release();
        wide.release();
    }
    size_t capacityBytes() const { return base.capacityBytes() + delta.capacityBytes() + wide.capacityBytes(); }
    // Sized to hold n pairs with `wideRows` wide blocks (contents not kept).
    void resizeDiscarding(size_t n, size_t wideRows);
    // Sized as `src` of n pairs is (its side table's room, contents not kept), then `src`'s pairs (on
    // this GPU or a peer) copied into it.
    void resizeLike(const DevicePairA& src, size_t n) { resizeDiscarding(n, src.wide.size() / PAIR_A_BLOCK); }
    void copyFromAsync(const DevicePairA& src, size_t n, Stream stream);
};

// The kernels of kernels/PairAKernels.cuh, from a module that includes them.
struct PairAKernels {
    CudaKernel wideBlocks, bases, put;
    void load(const CudaModule& m);
};

// Makes `out` the compact form of n As: from `whole` where given, else from detection's `offset`
// over `spheres` searched spheres (sphere k the A of pairs [offset[k], offset[k + 1])). Waits for the
// stream once to size the side table, where the set is large (a small one's has room for every
// block); `rows` is its scratch (a word per 32 pairs).
void compactPairAs(const PairAKernels& k, const bodyID_t* whole, const PairOffset* offset, unsigned int spheres,
                   size_t n, DevicePairA& out, DeviceBuffer<uint32_t>& rows, DevicePrimitives& prim, Stream stream);

// The host's n whole As onto the device in the compact form, and back (both wait for the stream).
void uploadPairAs(const std::vector<bodyID_t>& a, DevicePairA& d, Stream stream);
void downloadPairAs(const DevicePairA& d, size_t n, std::vector<bodyID_t>& a, Stream stream);

}  // namespace deme::cuda
