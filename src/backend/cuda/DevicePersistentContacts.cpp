#include "backend/cuda/DevicePersistentContacts.h"

#include <utility>

#include <deme/Error.h>

#include "jit/EmbeddedSources.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;
constexpr const char* kSourcePath = "backend/cuda/kernels/PersistentMerge.cu";

std::string sourceText(const std::string& call) {
    for (const jit::EmbeddedFile& f : jit::embeddedSources())
        if (kSourcePath == std::string(f.path)) return std::string(f.text, f.size);
    throwError(call, std::string("kernel source ") + kSourcePath + " is not embedded in this build");
}

}  // namespace

void DevicePersistentContacts::load(const std::string& call, const CudaCompileOptions& options) {
    const CudaCompileResult r = compileCudaSource(call, kSourcePath, sourceText(call), options);
    m_compileSeconds = r.compileSeconds;
    m_fromCache = r.cacheHit;
    m_module = CudaModule(call, r.image);
    m_missing = m_module.kernel("deme_persistent_missing");
    m_merge = m_module.kernel("deme_persistent_merge");
    m_flags = m_module.kernel("deme_persistent_flags");
}

void DevicePersistentContacts::uploadRules(const std::vector<WildcardArrays::ContactInit>& rules) {
    std::vector<ContactInitRule> r;
    for (const WildcardArrays::ContactInit& x : rules) r.push_back(ContactInitRule{x.a, x.b, x.index, x.value});
    m_rules.upload(r);
    m_numRules = (unsigned int)r.size();
}

unsigned int DevicePersistentContacts::merge(DeviceBuffer<bodyID_t>& geomA, DeviceBuffer<bodyID_t>& geomB,
                                             DeviceBuffer<uint8_t>& type, unsigned int nFresh, ContactKeys old,
                                             const uint8_t* oldType, const uint8_t* oldPersistent,
                                             DevicePrimitives& prim, Stream stream) {
    m_oldHadPersistent = false;
    if (old.n == 0) return nFresh;
    const ContactKeys fresh{geomA.data(), geomB.data(), nFresh};
    m_isMissing.resize((size_t)old.n + 1, stream);
    m_missingBefore.resize((size_t)old.n + 1, stream);
    m_any.resize(1, stream);
    m_isMissing.zeroAsync(stream);
    m_any.zeroAsync(stream);
    launch(m_missing, blocksFor(old.n, THREADS), THREADS, 0, stream, fresh, old, oldPersistent, m_isMissing.data(),
           m_any.data());
    prim.exclusiveSum(m_isMissing.data(), m_missingBefore.data(), (size_t)old.n + 1, stream);
    unsigned int counts[2] = {0, 0};  // missing pairs, any persistent
    m_missingBefore.downloadAsync(&counts[0], 1, stream, old.n);
    m_any.downloadAsync(&counts[1], 1, stream);
    synchronize(stream);
    m_oldHadPersistent = counts[1] != 0;
    if (counts[0] == 0) return nFresh;
    const unsigned int total = nFresh + counts[0];
    m_mergedA.resize(total, stream);
    m_mergedB.resize(total, stream);
    m_mergedType.resize(total, stream);
    launch(m_merge, blocksFor((unsigned long long)nFresh + old.n, THREADS), THREADS, 0, stream, fresh,
           (const uint8_t*)type.data(), old, oldType, (const unsigned int*)m_isMissing.data(),
           (const unsigned int*)m_missingBefore.data(), m_mergedA.data(), m_mergedB.data(), m_mergedType.data());
    // The merged arrays become the fresh set's; its former arrays are the next merge's scratch.
    std::swap(geomA, m_mergedA);
    std::swap(geomB, m_mergedB);
    std::swap(type, m_mergedType);
    return total;
}

void DevicePersistentContacts::carryOver(const StateView& view, ContactKeys fresh, const uint8_t* freshType,
                                         uint8_t* freshPersistent, float* freshWildcards, unsigned int W,
                                         ContactKeys old, const uint8_t* oldPersistent, Stream stream) {
    if (fresh.n == 0) return;
    launch(m_flags, blocksFor(fresh.n, THREADS), THREADS, 0, stream, view, fresh, freshType, old,
           m_oldHadPersistent ? oldPersistent : (const uint8_t*)nullptr, freshPersistent,
           (const ContactInitRule*)m_rules.data(), m_numRules, freshWildcards, W);
}

}  // namespace deme::cuda
