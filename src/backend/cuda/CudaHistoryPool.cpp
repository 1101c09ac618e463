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
    if (capacity >= PENDING_HISTORY_SLOT)
        throwError("DoDynamics", "the contact set's pooled history needs " + std::to_string(capacity) +
                                     " slots; at most " + std::to_string(PENDING_HISTORY_SLOT - 1) +
                                     " fit a slot's 31 bits");
    const MemoryGroupScope group(MemoryGroup::CONTACTS);
    // Kept: the slots' histories, and the forces a storing step paused in its pass has written.
    p.pool.resize(capacity * m_W, m_stream);
    DeviceBuffer<float3>& force = m_contacts[m_current].force;
    if (withForces || !force.empty()) force.resize(capacity, m_stream);
    p.capacity = (uint32_t)capacity;
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
    // Every claimed slot fits: the pending pairs' (the slots beyond the old capacity) too.
    growHistoryPool(m_poolPolicy.capacityFor(m_poolControlHost.used, m_numContacts), storing);
    // The pass again, over the pending pairs only (the pooled pass while `filling` is set), on the
    // state the paused pass read: the integration kernels stopped the batch before changing it.
    HistoryPoolControl fill = m_poolControlHost;
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
    HistoryPoolControl done = fill;
    done.filling = 0u;
    m_poolControl.uploadAsync(&done, 1, st);
    // The step's rest: integration, placement and the step's end, as the batch would have run them.
    LaunchList rest;
    recordStep(rest, settings, storing, true);
    rest.enqueue(st);
    m_control.downloadAsync(m_controlHost, 1, st);
    m_poolControl.downloadAsync(&m_poolControlHost, 1, st);
    synchronize(st);  // the host copies above stay alive until here
}

void CudaDynamics::downloadPooledHistory(ContactArrays& c) {
    const DeviceHistoryPool& p = m_pools[m_current];
    const size_t n = m_numContacts;
    std::vector<uint32_t> slots(n);
    std::vector<float> pool((size_t)p.capacity * m_W);
    if (n) p.slot.downloadAsync(slots.data(), n, m_stream);
    if (!pool.empty()) p.pool.downloadAsync(pool.data(), pool.size(), m_stream);
    const DeviceBuffer<float3>& force = m_contacts[m_current].force;
    std::vector<float3> forces(force.size() >= p.capacity ? p.capacity : 0);
    if (!forces.empty()) force.downloadAsync(forces.data(), forces.size(), m_stream);
    synchronize(m_stream);
    c.wildcards.resize(n * m_W);
    expandPooledHistory(slots.data(), n, pool.data(), m_W, c.wildcards.data());
    c.force.resize(n);
    if (forces.empty())
        std::fill(c.force.begin(), c.force.end(), float3{0.f, 0.f, 0.f});
    else
        expandPooledForces(slots.data(), n, forces.data(), c.force.data());
}

}  // namespace deme::cuda
