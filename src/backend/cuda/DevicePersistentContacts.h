// Persistent contacts and family initial contact wildcards on the GPU, at each re-detection: the
// CPU's rules (kinematics/HistoryMapping.cpp) run as the kernels of kernels/PersistentMerge.cu.
// DeviceSimulation calls merge() between the pair search and history mapping, and carryOver() right
// after history mapping; each contact set carries a persistent flag per pair, which the force model
// may change (kernels/ForcePassKernel.cuh) and the host may set (MarkPersistentContact, re-uploaded).
#pragma once

#include <vector>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DevicePrimitives.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "backend/cuda/kernels/PersistentArgs.cuh"
#include "state/SimState.h"
#include "state/StateView.h"

namespace deme::cuda {

class DevicePersistentContacts {
  public:
    // Compiles (or finds in the kernel cache) the kernels for `options`.
    void load(const std::string& call, const CudaCompileOptions& options);
    double compileSeconds() const { return m_compileSeconds; }
    bool fromCache() const { return m_fromCache; }

    // The family initial values of contact wildcards (WildcardArrays::contactInit), after upload.
    void uploadRules(const std::vector<WildcardArrays::ContactInit>& rules);

    // Adds to the fresh set (geomA, geomB, type: nFresh pairs, sorted) the persistent pairs of the
    // old set it lacks, in key order, growing the three buffers; returns the new count. Also
    // remembers whether the old set had any persistent pair, for carryOver().
    unsigned int merge(DeviceBuffer<bodyID_t>& geomA, DeviceBuffer<bodyID_t>& geomB, DeviceBuffer<uint8_t>& type,
                       unsigned int nFresh, ContactKeys old, const uint8_t* oldType, const uint8_t* oldPersistent,
                       DevicePrimitives& prim, Stream stream);
    // After history mapping into the fresh set: its persistent flags, and initial wildcards (W per
    // pair) of pairs new to the set. `view` gives the geometries' owners and families.
    void carryOver(const StateView& view, ContactKeys fresh, const uint8_t* freshType, uint8_t* freshPersistent,
                   float* freshWildcards, unsigned int W, ContactKeys old, const uint8_t* oldPersistent, Stream stream);

  private:
    CudaModule m_module;
    CudaKernel m_missing, m_merge, m_flags;
    DeviceBuffer<unsigned int> m_isMissing, m_missingBefore, m_any;
    DeviceBuffer<bodyID_t> m_mergedA, m_mergedB;
    DeviceBuffer<uint8_t> m_mergedType;
    DeviceBuffer<ContactInitRule> m_rules;
    unsigned int m_numRules = 0;
    bool m_oldHadPersistent = false;
    double m_compileSeconds = 0.0;
    bool m_fromCache = true;
};

}  // namespace deme::cuda
