// An owner's travel counts from the snapshot of the contact set in use (OwnerArrays::travel). An
// asynchronous order's set is detected from a later snapshot: the order keeps every owner's travel
// then, and once its set is installed each owner's travel counts from there. Written once for the
// CPU's loops (backend/cpu/CpuDynamics.cpp) and the GPU's kernels (kernels/Exchange.cu). Plain code:
// NVRTC compiles it.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

// What an owner travelled since an order's snapshot: its travel now less its travel then. Travel
// only grows between two installations, an order is taken (or dropped) before the next one, and a
// float difference of a >= b is never negative: so this is >= 0, the max a guard only.
DEME_HD_INLINE float travelSinceOrderSnapshot(float travel, float travelAtOrder) {
    const float d = travel - travelAtOrder;
    return d > 0.f ? d : 0.f;
}

}  // namespace deme
