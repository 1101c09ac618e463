// CudaDynamics' pooled contact history (state/HistoryPool.h, dynamics/PooledContactStep.h): the
// pool's room, the steps a full pool paused, and the host's per-pair copy of a pooled set.
#include <algorithm>
#include <string>
#include <vector>

#include <deme/Error.h>

#include "backend/cuda/CudaDynamics.h"
#include "state/HistoryPoolExpand.h"

namespace deme::cuda {

void CudaDynamics::resetHistoryPoolControl(uint32_t used) {
    m_poolControlHost = HistoryPoolControl{used, 0u, 0u, 0u};
    // From pageable memory: copied out before the call returns, so the host copy may change after.
    m_poolControl.uploadAsync(&m_poolControlHost, 1, m_stream);
}

void CudaDynamics::growHistoryPool(size_t capacity, bool withForces) {
    DeviceHistoryPool& p = m_pools[m_current];
    if (capacity <= p.capacity) return;
    if (capacity >= HISTORY_SLOT_LIMIT)
        throwError("DoDynamics", "the contact set's pooled history needs " + std::to_string(capacity) +
                                     " slots; a pool holds at most " + std::to_string(HISTORY_SLOT_LIMIT - 1));
    const MemoryGroupScope group(MemoryGroup::CONTACTS);
    // Kept: the slots' histories, and the forces a storing step paused in its pass has written.
    p.pool.resize(capacity * m_W, m_stream);
    DeviceBuffer<float3>& force = m_contacts[m_current].force;
    if (withForces || !force.empty()) force.resize(capacity, m_stream);
    p.capacity = (uint32_t)capacity;
    m_history.fitLateTable(p, m_stream);  // room for every late slot the pool can give
    refreshView();
}

void CudaDynamics::makeHistoryRoomBeforeBatch() {
    // Pauses are rare where the pool has a quarter to spare when a batch begins.
    const DeviceHistoryPool& p = m_pools[m_current];
    const size_t used = m_poolControlHost.used;
    if (used + used / 4 + m_poolPolicy.minSpare / 4 > p.capacity)
        growHistoryPool(m_poolPolicy.capacityFor(used, m_numContacts), false);
}

void CudaDynamics::finishPausedStep(const Settings& settings, bool storing) {
    const Stream st = m_stream;
    m_historyPauses++;
    if (m_poolControlHost.lost) lateTableFull();
    const uint32_t claims = m_poolControlHost.used;
    // Every claim fits: those the pass kept (below the old capacity) and those it could not (the
    // pairs left without a slot), which the fill claims again from the old capacity on.
    const uint32_t keptClaims = m_pools[m_current].capacity;
    growHistoryPool(m_poolPolicy.capacityFor(m_poolControlHost.used, m_numContacts), storing);
    // The pass again, over the pairs without a slot only (the pooled pass while `filling` is set),
    // on the state the paused pass read: the integration kernels stopped the batch before changing it.
    HistoryPoolControl fill = m_poolControlHost;
    fill.used = keptClaims;
    fill.paused = 0u;
    fill.filling = 1u;
    m_poolControl.uploadAsync(&fill, 1, st);
    StepBatchControl resumed = *m_controlHost;
    resumed.stop = 0u;
    m_control.uploadAsync(&resumed, 1, st);
    StateView fillView = m_view;
    if (!storing) fillView.contacts.force = nullptr;
    LaunchList pass;
    pass.overlapLaunches(false);
    const unsigned int tForce = settings.threadsPerBlock ? settings.threadsPerBlock : 256u;
    m_model.record(pass, fillView, m_control.data(), m_view.numClumps, m_view.numOwners - m_view.numClumps,
                   m_reduction.data(), tForce);
    pass.enqueue(st);
    // Once filled, the counter is where the paused pass left it: the fill claims exactly the claims
    // that pass could not keep (the same state and clock give the same decisions; checked below).
    HistoryPoolControl filled{};
    m_poolControl.downloadAsync(&filled, 1, st);
    HistoryPoolControl done = fill;
    done.used = claims;
    done.filling = 0u;
    m_poolControl.uploadAsync(&done, 1, st);
    // The step's rest: integration, placement and the step's end, as the batch would have run them.
    LaunchList rest;
    recordStep(rest, settings, storing, true);
    rest.enqueue(st);
    m_control.downloadAsync(m_controlHost, 1, st);
    m_poolControl.downloadAsync(&m_poolControlHost, 1, st);
    synchronize(st);  // the host copies above stay alive until here
    if (filled.lost) lateTableFull();
    if (filled.used != claims || filled.paused)
        throwError("DoDynamics", "internal: the pooled history's fill left " + std::to_string(filled.used) +
                                     " slots claimed where the paused pass claimed " + std::to_string(claims) +
                                     " (a pool of " + std::to_string(m_pools[m_current].capacity) + " slots)");
}

void CudaDynamics::lateTableFull() const {
    const DeviceHistoryPool& p = m_pools[m_current];
    throwError("DoDynamics", "internal: the pooled history's late table (" + std::to_string(p.lateTable.size()) +
                                 " entries, for a pool of " + std::to_string(p.capacity) + " slots, " +
                                 std::to_string(p.rankedSlots) + " of them ranked) is full");
}

void CudaDynamics::downloadPooledHistory(ContactArrays& c) {
    const DeviceHistoryPool& p = m_pools[m_current];
    const size_t n = m_numContacts;
    // The slots' form (12 bytes per 64 pairs, two bits a pair and the late table), read on the host
    // as the kernels read it: each pair's slot; and the mesh states, per ranked slot.
    std::vector<uint64_t> ranked(p.ranked.size()), late(p.late.size());
    std::vector<uint32_t> rankBase(p.rankBase.size());
    std::vector<unsigned long long> lateTable(p.lateTable.size());
    std::vector<float> pool((size_t)p.capacity * m_W);
    std::vector<uint8_t> meshStates(p.meshStateBySlot ? p.meshState.size() : 0);
    if (!meshStates.empty()) p.meshState.downloadAsync(meshStates.data(), meshStates.size(), m_stream);
    p.ranked.downloadAsync((unsigned long long*)ranked.data(), ranked.size(), m_stream);
    p.rankBase.downloadAsync(rankBase.data(), rankBase.size(), m_stream);
    p.late.downloadAsync((unsigned long long*)late.data(), late.size(), m_stream);
    p.lateTable.downloadAsync(lateTable.data(), lateTable.size(), m_stream);
    if (!pool.empty()) p.pool.downloadAsync(pool.data(), pool.size(), m_stream);
    const DeviceBuffer<float3>& force = m_contacts[m_current].force;
    std::vector<float3> forces(force.size() >= p.capacity ? p.capacity : 0);
    if (!forces.empty()) force.downloadAsync(forces.data(), forces.size(), m_stream);
    synchronize(m_stream);
    RankedSlotsView v;
    v.ranked = ranked.data();
    v.rankBase = rankBase.data();
    v.late = late.data();
    v.lateTable = lateTable.data();
    v.lateMask = (uint32_t)(lateTable.size() - 1);
    std::vector<uint32_t> slots(n);
    for (size_t i = 0; i < n; i++) slots[i] = slotOf(v, i);
    c.wildcards.resize(n * m_W);
    expandPooledHistory(slots.data(), n, pool.data(), m_W, c.wildcards.data());
    if (p.meshStateBySlot) {  // per ranked slot (every sphere-triangle pair is ranked); 0 for the rest
        c.meshState.assign(n, 0);
        for (size_t i = 0; i < n; i++)
            if (pairBit(v.ranked, i)) c.meshState[i] = meshStates[slots[i]];
    }
    c.force.resize(n);
    if (forces.empty())
        std::fill(c.force.begin(), c.force.end(), float3{0.f, 0.f, 0.f});
    else
        expandPooledForces(slots.data(), n, forces.data(), c.force.data());
}

}  // namespace deme::cuda
