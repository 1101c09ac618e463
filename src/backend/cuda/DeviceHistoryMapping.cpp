#include "backend/cuda/DeviceHistoryMapping.h"

#include <utility>

#include <deme/Error.h>

#include "backend/cuda/EmbeddedKernel.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;
constexpr const char* kSourcePath = "backend/cuda/kernels/HistoryMapping.cu";

ContactKeys keysOf(const DeviceContacts& c, unsigned int n) { return ContactKeys{c.geomA.data(), c.geomB.data(), n}; }

}  // namespace

void DeviceHistoryMapping::load(const std::string& call, const CudaCompileOptions& options) {
    const CudaCompileResult r = compileCudaSource(call, kSourcePath, embeddedKernelText(kSourcePath), options);
    m_compileSeconds = r.compileSeconds;
    m_fromCache = r.cacheHit;
    m_module = CudaModule(call, r.image);
    m_missing = m_module.kernel("deme_persistent_missing");
    m_merge = m_module.kernel("deme_persistent_merge");
    m_map = m_module.kernel("deme_map_history");
}

void DeviceHistoryMapping::uploadRules(const std::vector<ContactInitRule>& rules) {
    m_rules.upload(rules);
    m_numRules = (unsigned int)rules.size();
}

unsigned int DeviceHistoryMapping::mergePersistent(DeviceContacts& freshSet, unsigned int nFresh,
                                                   const DeviceContacts& oldSet, unsigned int nOld,
                                                   DevicePrimitives& prim, Stream stream) {
    m_oldHadPersistent = false;
    if (nOld == 0) return nFresh;
    const ContactKeys fresh = keysOf(freshSet, nFresh), old = keysOf(oldSet, nOld);
    const uint8_t* persistent = oldSet.persistent.data();
    // Whether the old set has any persistent pair at all (one byte read per pair). Most runs have
    // none: they need no per-pair scratch, which is let go (8 B per pair otherwise).
    m_any.resize(1, stream);
    m_any.zeroAsync(stream);
    launch(m_missing, blocksFor(nOld, THREADS), THREADS, 0, stream, fresh, old, persistent, (unsigned int*)nullptr,
           m_any.data());
    unsigned int any = 0;
    m_any.downloadAsync(&any, 1, stream);
    synchronize(stream);
    m_oldHadPersistent = any != 0;
    if (!any) {
        m_isMissing.release();
        m_missingBefore.release();
        return nFresh;
    }
    m_isMissing.resize((size_t)nOld + 1, stream);
    m_missingBefore.resize((size_t)nOld + 1, stream);
    m_isMissing.zeroAsync(stream);
    launch(m_missing, blocksFor(nOld, THREADS), THREADS, 0, stream, fresh, old, persistent, m_isMissing.data(),
           m_any.data());
    prim.exclusiveSum(m_isMissing.data(), m_missingBefore.data(), (size_t)nOld + 1, stream);
    unsigned int missing = 0;
    m_missingBefore.downloadAsync(&missing, 1, stream, nOld);
    synchronize(stream);
    if (missing == 0) return nFresh;
    const unsigned int total = nFresh + missing;
    m_mergedA.resize(total, stream);
    m_mergedB.resize(total, stream);
    launch(m_merge, blocksFor((unsigned long long)nFresh + nOld, THREADS), THREADS, 0, stream, fresh, old,
           (const unsigned int*)m_isMissing.data(), (const unsigned int*)m_missingBefore.data(), m_mergedA.data(),
           m_mergedB.data());
    // The merged arrays become the fresh set's; its former arrays are the next merge's scratch.
    std::swap(freshSet.geomA, m_mergedA);
    std::swap(freshSet.geomB, m_mergedB);
    return total;
}

unsigned int DeviceHistoryMapping::install(DeviceContacts& fresh, unsigned int nFresh, const DeviceContacts& old,
                                           unsigned int nOld, unsigned int W, const StateView& view,
                                           DevicePrimitives& prim, Stream stream) {
    const unsigned int total = mergePersistent(fresh, nFresh, old, nOld, prim, stream);
    resizeContactState(fresh, total, W);
    if (total == 0) return 0;
    const OldContactHistory history{keysOf(old, nOld),
                                    old.wildcards.data(),
                                    old.meshState.data(),
                                    m_oldHadPersistent ? old.persistent.data() : nullptr,
                                    W,
                                    m_rules.data(),
                                    m_numRules};
    launch(m_map, blocksFor(total, THREADS), THREADS, 0, stream, view, keysOf(fresh, total), history,
           fresh.wildcards.data(), fresh.meshState.data(), fresh.persistent.data());
    return total;
}

}  // namespace deme::cuda
