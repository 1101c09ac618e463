// Fills the force model's inputs (paper Table 3) for one contact of the active-contact set, from the
// state and its kinematic cache. Always inlined into the force loop, so that whatever a model does
// not use is never computed.
#pragma once

#include "physics/ContactGeometry.h"
#include "physics/ContactInputs.h"
#include "physics/RigidBody.h"
#include "runtime/SimState.h"

namespace deme {

inline bodyID_t contactOwnerB(const SimState& s, size_t c) {
    const bodyID_t b = s.contacts.geomB[c];
    return s.contacts.type[c] == SPHERE_SPHERE ? s.spheres.owner[b]
                                               : s.analytical.owner[b - (bodyID_t)s.spheres.size()];
}

inline double3 ownerPosition(const SimState& s, bodyID_t o) {
    const OwnerArrays& ow = s.owners;
    return decodePosition(ow.voxel[o], ow.subX[o], ow.subY[o], ow.subZ[o], s.frame);
}

DEME_HD_INLINE void gatherContactInputs(const SimState& s, size_t c, float time, float ts, ContactInputs& in) {
    const OwnerArrays& ow = s.owners;
    const KinematicCache& k = s.cache;
    const bodyID_t a = s.contacts.geomA[c];
    const bodyID_t b = s.contacts.geomB[c];
    const bodyID_t oA = s.spheres.owner[a];
    const bool ss = s.contacts.type[c] == SPHERE_SPHERE;
    const bodyID_t oB = ss ? s.spheres.owner[b] : s.analytical.owner[b - (bodyID_t)s.spheres.size()];

    in.bodyAPos = k.spherePos[a];
    in.ARadius = s.spheres.radius[a];
    in.bodyAMatType = s.spheres.material[a];
    ContactPoint cp;
    float3 offB;  // geometry B's reference point minus its owner's centre
    if (ss) {
        in.bodyBPos = k.spherePos[b];
        in.BRadius = s.spheres.radius[b];
        in.bodyBMatType = s.spheres.material[b];
        offB = k.sphereArm[b];
        cp = sphereSphereContact(in.bodyAPos, in.ARadius, in.bodyBPos, in.BRadius);
    } else {
        const size_t j = b - s.spheres.size();
        in.bodyBPos = k.analPos[j];
        in.BRadius = FLAT_SURFACE_RADIUS;
        in.bodyBMatType = s.analytical.material[j];
        offB = to_float3(in.bodyBPos - k.ownerPos[oB]);
        cp = s.analytical.type[j] == ANAL_PLANE
                 ? spherePlaneContact(in.bodyAPos, in.ARadius, in.bodyBPos, k.analDir[j])
                 : sphereCylinderContact(in.bodyAPos, in.ARadius, in.bodyBPos, k.analDir[j], s.analytical.radius[j],
                                         s.analytical.inside[j] != 0);
    }
    in.contactPnt = cp.point;
    in.B2A = cp.B2A;
    in.overlapDepth = cp.overlap;
    in.ts = ts;
    in.time = time;
    in.armA = to_float3(in.contactPnt - in.bodyAPos) + k.sphereArm[a];
    in.armB = to_float3(in.contactPnt - in.bodyBPos) + offB;
    in.AOwnerPos = k.ownerPos[oA];
    in.BOwnerPos = k.ownerPos[oB];
    in.AOriQ = ow.oriQ[oA];
    in.BOriQ = ow.oriQ[oB];
    in.locCPA = rotateToLocal(in.AOriQ, in.armA);
    in.locCPB = rotateToLocal(in.BOriQ, in.armB);
    in.rotVelCPA = cross(k.ownerAngVelGlobal[oA], in.armA);
    in.rotVelCPB = cross(k.ownerAngVelGlobal[oB], in.armB);
    in.AOwnerMass = s.massProps.mass[ow.inertia[oA]];
    in.BOwnerMass = s.massProps.mass[ow.inertia[oB]];
    in.AOwnerMOI = s.massProps.moi[ow.inertia[oA]];
    in.BOwnerMOI = s.massProps.moi[ow.inertia[oB]];
    in.AOwnerFamily = ow.family[oA];
    in.BOwnerFamily = ow.family[oB];
    in.ALinVel = ow.vel[oA];
    in.BLinVel = ow.vel[oB];
    in.ARotVel = ow.angVel[oA];
    in.BRotVel = ow.angVel[oB];
    in.AOwner = oA;
    in.BOwner = oB;
    in.AGeo = a;
    in.BGeo = b;
}

}  // namespace deme
