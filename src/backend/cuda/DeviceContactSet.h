// A contact set on dT's GPU, and the history-mapping step that hands a fresh set (from contact
// detection) the history of the set it replaces (ARCHITECTURE.md invariant 6). The step runs on dT's
// stream when dT installs a set, after the fresh pairs are in place and before the sets swap; other
// transfers of contact state from the old set to the fresh one (e.g. persistent contacts) belong to
// this step too.
#pragma once

#include <cstdint>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/CudaTypes.h"
#include "backend/cuda/DeviceBuffer.h"

#include <deme/VariableTypes.h>

namespace deme::cuda {

struct DeviceContacts {
    DeviceBuffer<bodyID_t> geomA, geomB;
    DeviceBuffer<uint8_t> type, meshState;
    DeviceBuffer<float> wildcards;
    DeviceBuffer<float3> force;  // per-contact torques are the CPU's reduction scratch only
    DeviceBuffer<uint8_t> persistent;  // per pair: kept when detection no longer finds it
    // Sizes the per-contact state for n pairs of W wildcards each (the pairs themselves are set by
    // whoever fills geomA, geomB, type).
    void resizeState(size_t n, unsigned int W) {
        meshState.resizeDiscarding(n);
        wildcards.resizeDiscarding(n * W);
        force.resizeDiscarding(n);
        persistent.resizeDiscarding(n);
    }
};

// History mapping, queued on `stream`: each pair of `fresh` (sorted by (A, B)) found in `old` (sorted
// likewise) keeps its wildcards and mesh state, a new pair starts from zero. `kMapHistory` is
// Detection.cu's deme_map_history, loaded on the GPU of both sets.
void mapContactHistory(const CudaKernel& kMapHistory, const DeviceContacts& old, uint32_t numOld,
                       DeviceContacts& fresh, uint32_t numFresh, unsigned int W, Stream stream);

}  // namespace deme::cuda
