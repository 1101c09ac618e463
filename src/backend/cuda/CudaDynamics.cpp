#include "backend/cuda/CudaDynamics.h"

#include <algorithm>
#include <cstddef>

#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"
#include "backend/cuda/Device.h"
#include "state/StateViewScalars.h"

namespace deme::cuda {

void CudaDynamics::refreshView() {
    m_state.viewInto(m_view);
    viewContacts(m_contacts[m_current], m_numContacts, m_view);
    // The voxel pretest (dynamics/ContactStep.h) for a large set of mostly apart pairs, the pairs that
    // touched in the last step run standing for the set's (none before any step: a scene assembled
    // with gaps, as most are), unless DEME_CUDA_VOXEL_PRETEST chose (m_voxelPretestForced).
    const bool byRule =
        m_numContacts >= VOXEL_PRETEST_MIN_PAIRS && 2 * m_lastRealContacts < (unsigned long long)m_numContacts;
    m_view.voxelPretest = m_view.spheresAreOwners && !m_view.frame.periodic.axes &&
                          (m_voxelPretestForced < 0 ? byRule : m_voxelPretestForced == 1);
    DeviceHistoryPool& p = m_pools[m_current];
    m_view.historyPool = p.view(m_poolControl.data());
}

void CudaDynamics::upload(const SimState& s, bool withContacts) {
    select();
    // A set's As are kept compact, each block's base naming a sphere below 2^31 (state/CompactPairA.h).
    // (The sets' bound on pairs holds a scene to fewer spheres still at six pairs a sphere:
    // runtime/IndexLimits.h.)
    if (s.spheres.size() >= COMPACT_A_SPHERE_LIMIT)
        throwError("Initialize", "a GPU run holds at most " + std::to_string(COMPACT_A_SPHERE_LIMIT - 1) +
                                     " spheres (the contact sets' compact ids); the scene has " +
                                     std::to_string(s.spheres.size()));
    const Stream st = m_stream;
    m_state.upload(s, st);
    if (withContacts) {
        // The contact set the host has (history included).
        returnForceMemory();  // both sets' arrays are rewritten or released here
        m_W = s.numWildcards;
        m_current = 0;
        m_numContacts = s.contacts.size();
        m_pairsForSlotShare = m_numContacts;
        m_setTrimmed = false;
        uploadContacts(s.contacts, m_W, m_contacts[0], st, m_history.modelWritesPersistent());
        m_contacts[1].force.release();  // only the set in use has per-contact forces
        // The host's set keeps W floats per pair: so does the uploaded one, until the next install.
        m_pools[0].release();
        m_pools[1].release();
    }
    m_motion.resizeDiscarding((size_t)MAX_BATCH_STEPS * NUM_FAMILIES);  // a batch's table (CudaStepBatch.cpp)
    m_reduction.resizeDiscarding(1);
    m_componentSpeed.resizeDiscarding(std::max<size_t>(1, s.analytical.size()));
    // Only the fused step reads the owners' sphere ranges (4 B per owner), and only where spheres
    // are not their owners (state/SphereLayout.h).
    if (m_fusedStep && s.triangles.size() == 0 && !s.spheresAreOwners)
        uploadResized(m_ownerSphereStart, s.ownerSphereStart, st);
    else
        m_ownerSphereStart.release();
    m_maxTravelBits.resizeDiscarding(1);
    synchronize(st);
    // The model's tables and wildcards and the persistence rules (copied on the legacy stream and
    // waited for, so dT's stream finds them in place).
    m_model.upload(s);
    m_history.uploadRules(s.wildcards.contactInit);
    synchronize(nullptr);

    setViewScalars(m_view, s);
    // A sheared cell's image offset follows the steps' clock in the control block (every replayed step
    // reads it there; physics/Periodic.h). Other scenes never read it.
    if (s.frame.periodic.shear)
        m_view.frame.periodic.shearClock = reinterpret_cast<const double*>(
            reinterpret_cast<const char*>(m_control.data()) + offsetof(StepBatchControl, time));
    m_domainDiagonal = length(s.domainSize);
    refreshView();
    m_subsetStale = true;
}

void CudaDynamics::download(SimState& s) {
    select();
    m_state.download(s, m_stream);
    synchronize(m_stream);
    m_model.download(s);
}

void CudaDynamics::downloadResults(SimState& s) {
    select();
    m_state.downloadResults(s, m_stream);
    synchronize(m_stream);
    s.owners.makeResults();  // (none on the device before the first upload: zero)
}

void CudaDynamics::gatherOwnerLoads(const std::vector<bodyID_t>& owners, float3* force, float3* torque) {
    select();
    const size_t n = owners.size();
    if (n == 0) return;
    // Before the first upload the device has no loads: zero, as the host's would be.
    if (m_state.owners.contactForce.size() != m_view.numOwners || m_view.numOwners == 0) {
        if (force) std::fill(force, force + n, make_float3(0.f));
        if (torque) std::fill(torque, torque + n, make_float3(0.f));
        return;
    }
    m_gatherIds.resizeDiscarding(n);
    m_gatherIds.uploadAsync(owners.data(), n, m_stream);
    m_gatheredLoads.resizeDiscarding(2 * n);
    constexpr unsigned int THREADS = 256;
    launch(kGatherOwnerLoads, blocksFor(n, THREADS), THREADS, 0, m_stream,
           (const float3*)m_state.owners.contactForce.data(), (const float3*)m_state.owners.contactTorque.data(),
           (const bodyID_t*)m_gatherIds.data(), (unsigned int)n, m_gatheredLoads.data());
    std::vector<float3> both(2 * n);
    m_gatheredLoads.downloadAsync(both.data(), 2 * n, m_stream);
    synchronize(m_stream);
    if (force) std::copy(both.begin(), both.begin() + n, force);
    if (torque) std::copy(both.begin() + n, both.end(), torque);
    // A large batch's scratch goes with it (a few rows' stays, for the next call).
    if (n > GATHER_KEPT_ROWS) {
        m_gatherIds.release();
        m_gatheredLoads.release();
    }
}

void CudaDynamics::downloadContacts(SimState& s) {
    select();
    cuda::downloadContacts(m_contacts[m_current], m_numContacts, m_W, s.contacts, m_stream, !historyPooled());
    if (historyPooled()) downloadPooledHistory(s.contacts);  // synchronises
    synchronize(m_stream);
}

void CudaDynamics::uploadTrackerLoads(const SimState& s) {
    select();
    m_state.uploadTrackerLoads(s, m_stream);
    // The host vectors may change (or go) before the next step reads them.
    synchronize(m_stream);
}

void CudaDynamics::downloadStepFlags(std::vector<uint8_t>& flags) {
    select();
    const DeviceBuffer<uint8_t>& d = m_state.integrationScratch.flags;
    flags.resize(d.size());
    if (!flags.empty()) d.downloadAsync(flags.data(), flags.size(), m_stream);
    synchronize(m_stream);
}

void CudaDynamics::beginRun(const Settings& settings, const FamilyRules& families) {
    // dT's GPU stays current for the call's steps (and the contact-set work between them).
    select();
    m_asyncDetection = settings.asyncDetection;
    prepareFamilyMotion(families);
    m_anyFamilyFixed = families.anyFixed();
    m_subsetStale = true;
}

std::string CudaDynamics::description() const { return "GPU " + std::to_string(m_device) + " (" + m_name + ")"; }

void CudaDynamics::countRunMemory(size_t bytes[NUM_MEMORY_GROUPS]) const {
    for (int g = 0; g < NUM_MEMORY_GROUPS; g++) bytes[g] = deviceBytesInGroup((MemoryGroup)g);
}

size_t CudaDynamics::expectedSlotsWithHistory(size_t pairs, unsigned int W) const {
    HistoryPoolPolicy policy = m_poolPolicy;
    policy.W = W;  // (the set's, known before the first upload)
    if (!policy.considers(pairs)) return DENSE_HISTORY;
    size_t withSlot = 0;
    if (m_pairsForSlotShare > 0) {
        if (!historyPooled()) return DENSE_HISTORY;
        // The pool's slots in use as last read back (CudaHistoryPool.cpp), for the set's pairs
        // before any trim, at the new set's size.
        withSlot = (size_t)((double)m_poolControlHost.used * (double)pairs / (double)m_pairsForSlotShare + 0.5);
    }
    return policy.chooses(pairs, withSlot) ? withSlot : DENSE_HISTORY;
}

size_t CudaDynamics::expectedHistorySlots(size_t pairs, unsigned int W) const {
    const size_t withSlot = expectedSlotsWithHistory(pairs, W);
    return withSlot == DENSE_HISTORY ? DENSE_HISTORY : m_poolPolicy.capacityFor(withSlot, pairs);
}

size_t CudaDynamics::expectedLateSlots(size_t pairs, unsigned int W) const {
    const size_t withSlot = expectedSlotsWithHistory(pairs, W);
    return withSlot == DENSE_HISTORY ? 0 : m_poolPolicy.capacityFor(withSlot, pairs) - withSlot;
}

size_t CudaDynamics::memoryAvailable() const {
    select();
    size_t freeBytes = 0, totalBytes = 0;
    if (cudaMemGetInfo(&freeBytes, &totalBytes) != cudaSuccess) {
        cudaGetLastError();
        return 0;
    }
    return freeBytes;
}

}  // namespace deme::cuda
