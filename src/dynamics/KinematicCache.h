// Keeps SimState::cache in step with the owner state.
#pragma once

#include "physics/RigidBody.h"
#include "state/SimState.h"

namespace deme {

// Recomputes the cached quantities of owner o and its spheres from the stored state.
inline void updateOwnerCache(SimState& s, size_t o) {
    const OwnerArrays& ow = s.owners;
    KinematicCache& k = s.cache;
    const double3 p = decodePosition(ow.voxel[o], ow.subX[o], ow.subY[o], ow.subZ[o], s.frame);
    const float4 q = ow.oriQ[o];
    k.ownerPos[o] = p;
    k.ownerAngVelGlobal[o] = rotateToGlobal(q, ow.angVel[o]);
    for (uint32_t i = s.ownerSphereStart[o]; i < s.ownerSphereStart[o + 1]; i++) {
        const float3 rel = s.spheres.relPos[i];
        // Most clumps are single spheres at their centre: no rotation needed.
        const bool centred = rel.x == 0.f && rel.y == 0.f && rel.z == 0.f;
        const double3 arm = centred ? make_double3(0.0, 0.0, 0.0) : rotateToGlobal(q, to_double3(rel));
        k.spherePos[i] = p + arm;
        k.sphereArm[i] = to_float3(arm);
    }
    const TriangleArrays& t = s.triangles;
    for (uint32_t i = s.ownerTriStart[o]; i < s.ownerTriStart[o + 1]; i++) {
        k.triVert[3 * i + 0] = localPointToGlobal(p, q, t.v0[i]);
        k.triVert[3 * i + 1] = localPointToGlobal(p, q, t.v1[i]);
        k.triVert[3 * i + 2] = localPointToGlobal(p, q, t.v2[i]);
    }
}

// Analytical components in the global frame (few; done serially).
void updateAnalyticalCache(SimState& s);

// Everything, e.g. after Initialize or a host-side change of the state.
void refreshKinematicCache(SimState& s);

}  // namespace deme
