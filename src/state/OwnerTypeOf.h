// An owner's type (OWNER_CLUMP, OWNER_ANALYTICAL, OWNER_MESH) follows from its place among the owners
// (clumps first, then analytical objects, then meshes: SimState::numClumps and numAnalyticalOwners,
// kept so by the assembly and every scene edit), so no array stores it: one byte an owner less on
// the host and on the GPU. Written once for the host state and the views. Plain code: NVRTC
// compiles it.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

template <class S>
DEME_HD_INLINE uint8_t ownerTypeOf(const S& s, size_t o) {
    return o < (size_t)s.numClumps                                   ? (uint8_t)OWNER_CLUMP
           : o < (size_t)s.numClumps + (size_t)s.numAnalyticalOwners ? (uint8_t)OWNER_ANALYTICAL
                                                                     : (uint8_t)OWNER_MESH;
}

}  // namespace deme
