// One owner's family change on a condition (DEMSolver::ChangeFamilyWhen), written once for the
// CPU's loop (backend/cpu/FamilyChanges.cpp) and the GPU's generated kernel
// (codegen/FamilyConditionSource.cpp). The conditions themselves are the user's: evaluated from
// their bytecode on the CPU, compiled into the kernel on the GPU; what they read and what a match
// does is here.
#pragma once

#include "state/FamilyStepMotion.h"
#include "state/OwnerCentre.h"
#include "state/OwnerTypeOf.h"

namespace deme {

// How many values a condition reads: X, Y, Z, Vx, Vy, Vz, t (codegen/FamilyCondition.h).
constexpr int FAMILY_CONDITION_VARS = 7;

// Owner o's condition inputs: its centre of mass and velocity (global frame) and the time.
template <class S>
DEME_HD_INLINE void familyConditionInputs(const S& s, size_t o, double t, double* v) {
    const double3 p = ownerCentre(s, o);
    const float3 vel = s.owners.vel[o];
    v[0] = p.x;
    v[1] = p.y;
    v[2] = p.z;
    v[3] = (double)vel.x;
    v[4] = (double)vel.y;
    v[5] = (double)vel.z;
    v[6] = t;
}

// Whether rule (from -> to) with condition value `holds` (non-zero: true) moves owner o; if so its
// family becomes `to`. Rules are tried in the order they were given and the first match wins, so an
// owner changes family at most once per check (a chain a -> b -> c takes two checks). Only clumps
// change: walls and meshes keep the family they were given (a box condition such as "X > 1" would
// otherwise catch the floor, whose centre is a point of the plane).
template <class S>
DEME_HD_INLINE bool applyFamilyRule(S& s, size_t o, family_t from, family_t to, double holds) {
    if (ownerTypeOf(s, o) != OWNER_CLUMP || s.owners.family[o] != from || holds == 0.0) return false;
    s.owners.family[o] = to;
    return true;
}

}  // namespace deme
