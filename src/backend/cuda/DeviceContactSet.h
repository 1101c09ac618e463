// The history-mapping step that hands a fresh contact set (from contact detection) the history of
// the set it replaces on dT's GPU (ARCHITECTURE.md invariant 6). It runs on dT's stream when dT
// installs a set (CudaContactSets.cpp), after the fresh pairs are in place and before the sets swap.
#pragma once

#include <cstdint>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/CudaTypes.h"
#include "backend/cuda/DeviceState.h"

namespace deme::cuda {

// History mapping, queued on `stream`: each pair of `fresh` (sorted by (A, B)) found in `old` (sorted
// likewise) keeps its wildcards and mesh state, a new pair starts from zero. `kMapHistory` is
// Detection.cu's deme_map_history, loaded on the GPU of both sets.
void mapContactHistory(const CudaKernel& kMapHistory, const DeviceContacts& old, uint32_t numOld,
                       DeviceContacts& fresh, uint32_t numFresh, unsigned int W, Stream stream);

}  // namespace deme::cuda
