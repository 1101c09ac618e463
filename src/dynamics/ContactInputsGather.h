// Fills the force model's inputs (paper Table 3) for one contact of the active-contact set.
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

inline void gatherContactInputs(const SimState& s, size_t c, float time, float ts, ContactInputs& in) {
    const OwnerArrays& ow = s.owners;
    const bodyID_t a = s.contacts.geomA[c];
    const bodyID_t b = s.contacts.geomB[c];
    const bodyID_t oA = s.spheres.owner[a];
    const bodyID_t oB = contactOwnerB(s, c);

    in.AOwnerPos = ownerPosition(s, oA);
    in.BOwnerPos = ownerPosition(s, oB);
    in.AOriQ = ow.oriQ[oA];
    in.BOriQ = ow.oriQ[oB];
    in.bodyAPos = localPointToGlobal(in.AOwnerPos, in.AOriQ, s.spheres.relPos[a]);
    in.ARadius = s.spheres.radius[a];
    in.bodyAMatType = s.spheres.material[a];

    ContactPoint cp;
    if (s.contacts.type[c] == SPHERE_SPHERE) {
        in.bodyBPos = localPointToGlobal(in.BOwnerPos, in.BOriQ, s.spheres.relPos[b]);
        in.BRadius = s.spheres.radius[b];
        in.bodyBMatType = s.spheres.material[b];
        cp = sphereSphereContact(in.bodyAPos, in.ARadius, in.bodyBPos, in.BRadius);
    } else {
        const size_t k = b - s.spheres.size();
        in.bodyBPos = localPointToGlobal(in.BOwnerPos, in.BOriQ, s.analytical.relPos[k]);
        const double3 dir = to_double3(rotateToGlobal(in.BOriQ, s.analytical.relDir[k]));
        in.BRadius = FLAT_SURFACE_RADIUS;
        in.bodyBMatType = s.analytical.material[k];
        cp = s.analytical.type[k] == ANAL_PLANE
                 ? spherePlaneContact(in.bodyAPos, in.ARadius, in.bodyBPos, dir)
                 : sphereCylinderContact(in.bodyAPos, in.ARadius, in.bodyBPos, dir, s.analytical.radius[k],
                                         s.analytical.inside[k] != 0);
    }
    in.contactPnt = cp.point;
    in.B2A = cp.B2A;
    in.overlapDepth = cp.overlap;
    in.ts = ts;
    in.time = time;
    in.locCPA = rotateToLocal(in.AOriQ, to_float3(in.contactPnt - in.AOwnerPos));
    in.locCPB = rotateToLocal(in.BOriQ, to_float3(in.contactPnt - in.BOwnerPos));
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
