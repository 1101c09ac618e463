#include "backend/cuda/DevicePairA.h"

#include "backend/cuda/DevicePrimitives.h"
#include "state/CompactPairAHost.h"
#include "state/SimState.h"

namespace deme::cuda {

namespace {
constexpr unsigned int THREADS = 256;
// A set whose As would take at most this whole gets room for every block to be wide (at most 4 B a
// pair more, where the bytes do not matter): its side table is sized without waiting for the wide
// blocks' count, a host round trip each detection of a lab-scale run would otherwise make.
constexpr size_t ROOM_FOR_EVERY_WIDE_BLOCK_UP_TO = KEEP_REBUILT_ARRAYS_UP_TO;
}  // namespace

void DevicePairA::resizeDiscarding(size_t n, size_t wideRows) {
    base.resizeDiscarding(pairABlocks(n));
    delta.resizeDiscarding(n);
    wide.resizeDiscarding(wideRows * PAIR_A_BLOCK);
}

void DevicePairA::copyFromAsync(const DevicePairA& src, size_t n, Stream stream) {
    if (n == 0) return;
    base.copyFromAsync(src.base, base.size(), stream);
    delta.copyFromAsync(src.delta, n, stream);
    if (!wide.empty()) wide.copyFromAsync(src.wide, wide.size(), stream);
}

void PairAKernels::load(const CudaModule& m) {
    wideBlocks = m.kernel("deme_pair_a_wide_blocks");
    bases = m.kernel("deme_pair_a_bases");
    put = m.kernel("deme_pair_a_put");
}

void compactPairAs(const PairAKernels& k, const bodyID_t* whole, const PairOffset* offset, unsigned int spheres,
                   size_t n, DevicePairA& out, DeviceBuffer<uint32_t>& rows, DevicePrimitives& prim, Stream stream) {
    const size_t blocks = pairABlocks(n);
    if (n == 0) {
        out.resizeDiscarding(0, 0);
        return;
    }
    const unsigned long long pairs = n;
    rows.resizeDiscarding(blocks + 1);
    rows.zeroAsync(stream);  // the last entry stays 0 for the exclusive sum
    launch(k.wideBlocks, blocksFor(blocks, THREADS), THREADS, 0, stream, whole, offset, spheres, pairs, rows.data());
    prim.exclusiveSum(rows.data(), rows.data(), blocks + 1, stream);
    if (n * sizeof(bodyID_t) <= ROOM_FOR_EVERY_WIDE_BLOCK_UP_TO) {
        out.resizeDiscarding(n, blocks);
    } else {
        uint32_t wideRows = 0;
        rows.downloadAsync(&wideRows, 1, stream, blocks);
        synchronize(stream);
        out.resizeDiscarding(n, wideRows);
    }
    launch(k.bases, blocksFor(blocks, THREADS), THREADS, 0, stream, whole, offset, spheres, pairs,
           (const uint32_t*)rows.data(), out.base.data());
    launch(k.put, blocksFor(whole ? n : spheres, THREADS), THREADS, 0, stream, whole, offset, spheres, pairs,
           out.writer());
}

void uploadPairAs(const std::vector<bodyID_t>& a, DevicePairA& d, Stream stream) {
    const HostCompactPairAs c = compactPairAsOnHost(a.data(), a.size());
    d.resizeDiscarding(a.size(), c.wide.size() / PAIR_A_BLOCK);
    if (!c.base.empty()) d.base.uploadAsync(c.base.data(), c.base.size(), stream);
    if (!c.delta.empty()) d.delta.uploadAsync(c.delta.data(), c.delta.size(), stream);
    if (!c.wide.empty()) d.wide.uploadAsync(c.wide.data(), c.wide.size(), stream);
    synchronize(stream);  // the host's copy goes with this call
}

void downloadPairAs(const DevicePairA& d, size_t n, std::vector<bodyID_t>& a, Stream stream) {
    HostCompactPairAs c;
    c.base.resize(pairABlocks(n));
    c.delta.resize(n);
    c.wide.resize(d.wide.size());
    if (n) {
        d.base.downloadAsync(c.base.data(), c.base.size(), stream);
        d.delta.downloadAsync(c.delta.data(), n, stream);
        if (!c.wide.empty()) d.wide.downloadAsync(c.wide.data(), c.wide.size(), stream);
    }
    synchronize(stream);
    a.resize(n);
    expandPairAs(c.list(), n, a.data());
}

}  // namespace deme::cuda
