// Installing a freshly detected contact set on the GPU with the history of the set it replaces: the
// rules of kinematics/HistoryRules.h run as the kernels of kernels/HistoryMapping.cu, on dT's stream
// (CudaContactSets.cpp calls it when dT installs a set). Each contact set carries a persistent flag
// per pair, which the force model may change and the host may set (MarkPersistentContact,
// re-uploaded).
#pragma once

#include <functional>
#include <vector>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DeviceHistoryPool.h"
#include "backend/cuda/DevicePrimitives.h"
#include "backend/cuda/DeviceState.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "kinematics/HistoryRules.h"
#include "state/SimState.h"
#include "state/StateView.h"

namespace deme::cuda {

class DeviceHistoryMapping {
  public:
    // Compiles (or finds in the kernel cache) the kernels for `options`.
    void load(const std::string& call, const CudaCompileOptions& options);
    double compileSeconds() const { return m_compileSeconds; }
    bool fromCache() const { return m_fromCache; }

    // The family initial values of contact wildcards (WildcardArrays::contactInit), after upload.
    void uploadRules(const std::vector<ContactInitRule>& rules);
    // Whether the force model may set a pair's persistent flag (a custom model): then every set
    // keeps flags; otherwise only a set with a persistent pair does (1 B a pair, as on the CPU).
    void setModelWritesPersistent(bool writes) { m_modelWritesPersistent = writes; }
    bool modelWritesPersistent() const { return m_modelWritesPersistent; }

    // Makes `fresh` (its first nFresh pairs set by detection, sorted) the new set: adds the
    // persistent pairs of `old` (nOld pairs) it lacks, in key order, sizes its per-contact state and
    // carries every pair's history over, from `old`'s wildcards or pool (`oldPool.active`), into
    // fresh's wildcards or a pool (freshPool, where `policy` chooses it; its `used` slots are then
    // `slotsUsed`). Returns the new set's size. `view` gives the geometries' owners and families.
    size_t install(DeviceContacts& fresh, DeviceHistoryPool& freshPool, size_t nFresh, const DeviceContacts& old,
                   const DeviceHistoryPool& oldPool, size_t nOld, unsigned int W, const HistoryPoolPolicy& policy,
                   const StateView& view, DevicePrimitives& prim, Stream stream, uint32_t& slotsUsed);

    // Before a synchronous detection: `set` (n pairs, its history in its wildcards or in `pool`)
    // keeps only the pairs that hand something to the next set (pairHandsOn), where the rules of
    // kinematics/CarriedPairsRule.h allow it and it pays; n becomes the count kept. Returns whether
    // it trimmed: the set then serves no step, only the next installation (the pool keeps its
    // slots, and the trimmed pairs theirs, as late pairs). `beforeTrim` runs once it is decided, before the set
    // changes.
    bool keepOnlyPairsHandedOn(DeviceContacts& set, DeviceHistoryPool& pool, size_t& n, unsigned int W,
                               DevicePrimitives& prim, Stream stream, const std::function<void()>& beforeTrim);

    // `pool`'s late table made lateTableEntriesFor(pool.capacity, pool.rankedSlots) entries where it
    // has fewer, its entries kept (CudaDynamics::growHistoryPool).
    void fitLateTable(DeviceHistoryPool& pool, Stream stream);

  private:
    // Each word's first rank of `pool`'s ranked bits (the pairs marked); returns the marked pairs'
    // count (summed in 64 bits: the ranks are valid where it is below 2^32).
    uint64_t rankMarkedPairs(DeviceHistoryPool& pool, DevicePrimitives& prim, Stream stream);
    // Each of `numWords` words' first rank of `marks` into `rankBase` (numWords + 1 entries); returns
    // the marked pairs' count, summed in 64 bits.
    uint64_t rankMarks(const unsigned long long* marks, size_t numWords, DeviceBuffer<uint32_t>& rankBase,
                       DevicePrimitives& prim, Stream stream);
    // Adds the missing persistent pairs to fresh's pair arrays; returns the new count. Sets
    // m_oldHadPersistent.
    size_t mergePersistent(DeviceContacts& fresh, size_t nFresh, const DeviceContacts& old, size_t nOld,
                           DevicePrimitives& prim, Stream stream);

    CudaModule m_module;
    CudaKernel m_missing, m_merge, m_map, m_markSlots, m_mapPooled, m_markMesh, m_markCarried, m_mapMarked,
        m_markHandedOn, m_countMarks, m_keepHandedOn, m_rehashLate;
    PairAKernels m_pairAKernels;         // merged and trimmed sets' As made compact
    DeviceBuffer<uint32_t> m_pairARows;  // their scratch
    DeviceBuffer<unsigned long long> m_isMissing, m_missingBefore;  // per old pair, 64-bit sums
    DeviceBuffer<unsigned int> m_any;
    DeviceBuffer<uint64_t> m_marked;  // rankMarks' count
    DeviceBuffer<bodyID_t> m_mergedA, m_mergedB;
    DeviceBuffer<ContactInitRule> m_rules;
    unsigned int m_numRules = 0;
    bool m_oldHadPersistent = false;
    bool m_modelWritesPersistent = true;
    double m_compileSeconds = 0.0;
    bool m_fromCache = true;
};

}  // namespace deme::cuda
