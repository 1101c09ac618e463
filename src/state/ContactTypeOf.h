// A contact's type (SPHERE_SPHERE, SPHERE_ANALYTICAL, SPHERE_TRIANGLE) follows from its B geometry's
// place in the unified id space (spheres, then analytical components, then triangles; A is always a
// sphere), so no set stores it: one byte a pair less in every set, on the host and on the GPU.
// Written once for the host state and the views. Plain code: NVRTC compiles it.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

// The type of a pair (sphere, b).
template <class S>
DEME_HD_INLINE uint8_t contactTypeOf(const S& s, bodyID_t b) {
    return b < s.analyticalIdBase() ? (uint8_t)SPHERE_SPHERE
           : b < s.triangleIdBase() ? (uint8_t)SPHERE_ANALYTICAL
                                    : (uint8_t)SPHERE_TRIANGLE;
}

// Contact i's type in the state's (or view's) set.
template <class S>
DEME_HD_INLINE uint8_t contactTypeAt(const S& s, size_t i) {
    return contactTypeOf(s, s.contacts.geomB[i]);
}

}  // namespace deme
