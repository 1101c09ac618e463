// Where a sphere's centre and arm are read. Most large scenes are clumps of one sphere each, at the
// clump's centre (the mixer's grains, a drum's, a billion-sphere bed): there a sphere's centre is its
// owner's, its arm is zero and its offset in the owner's frame is zero, so the state keeps none of
// the three arrays (spheres.relPos, cache.spherePos, cache.sphereArm: 48 bytes a sphere) and the
// steps place no spheres. `spheresAreOwners` says a state is laid out so: sphere i is then owner i's
// only sphere (runtime/SphereLayoutChoice.h decides and switches). Every reader goes through the
// functions below, written once for the host state and the GPU's view. Plain code: NVRTC compiles it.
#pragma once

#include <deme/VariableTypes.h>

#include "state/OwnerCentre.h"

namespace deme {

// The first element of a state array: a host vector's or a view's pointer.
template <class T>
DEME_HD_INLINE const T* arrayData(const T* p) {
    return p;
}
template <class V>
DEME_HD_INLINE const typename V::value_type* arrayData(const V& v) {
    return v.data();
}

// Sphere i's centre, global frame: its owner's, decoded from the compact position, where spheres
// are their owners (state/OwnerCentre.h).
template <class S>
DEME_HD_INLINE double3 sphereCentre(const S& s, size_t i) {
    return s.spheresAreOwners ? ownerCentre(s, i) : s.cache.spherePos[i];
}

// Sphere i's owner: sphere i itself where spheres are their owners (one dependent read fewer for a
// contact's owners).
template <class S>
DEME_HD_INLINE bodyID_t sphereOwner(const S& s, size_t i) {
    return s.spheresAreOwners ? (bodyID_t)i : s.spheres.owner[i];
}

// Sphere i's centre minus its owner's centre, global frame.
template <class S>
DEME_HD_INLINE float3 sphereArmOf(const S& s, size_t i) {
    return s.spheresAreOwners ? make_float3(0.f, 0.f, 0.f) : s.cache.sphereArm[i];
}

// Sphere i's centre in its owner's frame.
template <class S>
DEME_HD_INLINE float3 sphereRelPos(const S& s, size_t i) {
    return s.spheresAreOwners ? make_float3(0.f, 0.f, 0.f) : s.spheres.relPos[i];
}

}  // namespace deme
