// Fills the force model's inputs (paper Table 3) for one contact of the active-contact set, from the
// state and its kinematic cache. Always inlined into the force loop, so that whatever a model does
// not use is never computed. Templates over the state type: SimState on the CPU, a StateView of
// device memory on the GPU (same member names).
#pragma once

#include "physics/ContactGeometry.h"
#include "physics/ContactInputs.h"
#include "physics/Periodic.h"
#include "physics/RigidBody.h"
#include "state/ContactTypeOf.h"
#include "state/SphereLayout.h"

namespace deme {

template <class S>
DEME_HD_INLINE bodyID_t geometryOwner(const S& s, uint8_t type, bodyID_t b) {
    return type == SPHERE_SPHERE       ? sphereOwner(s, b)
           : type == SPHERE_ANALYTICAL ? s.analytical.owner[b - s.analyticalIdBase()]
                                       : s.triangles.owner[b - s.triangleIdBase()];
}

template <class S>
DEME_HD_INLINE bodyID_t contactOwnerB(const S& s, size_t c) {
    return geometryOwner(s, contactTypeAt(s, c), s.contacts.geomB[c]);
}

// Across a periodic face (physics/Periodic.h): the shift that takes triangle `tri` to its image
// nearest to the point x (zero without periodic axes).
template <class S>
DEME_HD_INLINE double3 triangleImageShift(const S& s, size_t tri, const double3& x) {
    return imageShift(s.frame.periodic, x - s.cache.triVert[3 * tri]);
}

// Sphere-triangle geometry: closest point on the triangle, its barycentric coordinates, and the
// contact it makes with sphere a, in the sphere's frame (the triangle's image nearest to it).
template <class S>
DEME_HD_INLINE ContactPoint sphereTriangleGeometry(const S& s, bodyID_t a, size_t tri, double3& onTri,
                                                   double3& bary) {
    const double3* v = &s.cache.triVert[3 * tri];
    const double3 x = sphereCentre(s, a);
    const double3 shift = triangleImageShift(s, tri, x);
    onTri = closestPointOnTriangle(x, v[0] + shift, v[1] + shift, v[2] + shift, bary);
    const double3 nrm = cross(v[1] - v[0], v[2] - v[0]);
    return sphereTriangleContact(x, s.spheres.radius[a], onTri, nrm / length(nrm));
}

// Contact c's inputs, its geometries a and b given (read where the caller chose). `type` is the
// contact's type; callers that pass a constant get a path without the other branches.
template <class S>
DEME_HD_INLINE void gatherContactInputsOfType(const S& s, bodyID_t a, bodyID_t b, uint8_t type, float time, float ts,
                                              ContactInputs& in) {
    const auto& ow = s.owners;
    const auto& k = s.cache;
    const bodyID_t oA = sphereOwner(s, a);
    const bodyID_t oB = geometryOwner(s, type, b);

    in.bodyAPos = sphereCentre(s, a);
    in.ARadius = s.spheres.radius[a];
    in.bodyAMatType = s.spheres.material[a];
    ContactPoint cp;
    float3 offB;  // geometry B's reference point minus its owner's centre
    // Across a periodic face, B is taken in its image nearest to A: positions of B and its owner are
    // shifted by this (zero without periodic axes, and for analytical boundaries, which periodic
    // shifts leave as they are), and in a sheared cell its velocity by imageVelocity.
    double3 shiftB = make_double3(0.0, 0.0, 0.0);
    double3 ownerB;  // B's owner's centre, decoded once (state/OwnerCentre.h)
    if (type == SPHERE_SPHERE) {
        const double3 centreB = sphereCentre(s, b);
        shiftB = imageShift(s.frame.periodic, in.bodyAPos - centreB);
        in.bodyBPos = centreB + shiftB;
        in.BRadius = s.spheres.radius[b];
        in.bodyBMatType = s.spheres.material[b];
        offB = sphereArmOf(s, b);
        ownerB = s.spheresAreOwners ? centreB : ownerCentre(s, oB);
        cp = sphereSphereContact(in.bodyAPos, in.ARadius, in.bodyBPos, in.BRadius);
    } else if (type == SPHERE_TRIANGLE) {
        const size_t t = b - s.triangleIdBase();
        const double3* v = &k.triVert[3 * t];
        const double3 centroid = (v[0] + v[1] + v[2]) / 3.0;
        shiftB = triangleImageShift(s, t, in.bodyAPos);
        in.bodyBPos = centroid + shiftB;
        in.BRadius = FLAT_SURFACE_RADIUS;
        in.bodyBMatType = s.triangles.material[t];
        ownerB = ownerCentre(s, oB);
        offB = to_float3(centroid - ownerB);
        double3 onTri, bary;
        cp = sphereTriangleGeometry(s, a, t, onTri, bary);
    } else {
        const size_t j = b - s.analyticalIdBase();
        in.bodyBPos = k.analPos[j];
        in.BRadius = FLAT_SURFACE_RADIUS;
        in.bodyBMatType = s.analytical.material[j];
        ownerB = ownerCentre(s, oB);
        offB = to_float3(in.bodyBPos - ownerB);
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
    in.armA = to_float3(in.contactPnt - in.bodyAPos) + sphereArmOf(s, a);
    in.armB = to_float3(in.contactPnt - in.bodyBPos) + offB;
    // A sphere that is its owner has its centre already (decoded once, state/OwnerCentre.h).
    in.AOwnerPos = s.spheresAreOwners ? in.bodyAPos : ownerCentre(s, oA);
    in.BOwnerPos = ownerB + shiftB;
    in.AOriQ = ow.oriQ[oA];
    in.BOriQ = ow.oriQ[oB];
    in.locCPA = rotateToLocal(in.AOriQ, in.armA);
    in.locCPB = rotateToLocal(in.BOriQ, in.armB);
    // The owners' spins in the global frame, from what is read anyway (no cached copy: 12 bytes an
    // owner).
    in.rotVelCPA = cross(rotateToGlobal(in.AOriQ, ow.angVel[oA]), in.armA);
    in.rotVelCPB = cross(rotateToGlobal(in.BOriQ, ow.angVel[oB]), in.armB);
    in.AOwnerMass = s.massProps.mass[ow.inertia[oA]];
    in.BOwnerMass = s.massProps.mass[ow.inertia[oB]];
    in.AOwnerMOI = s.massProps.moi[ow.inertia[oA]];
    in.BOwnerMOI = s.massProps.moi[ow.inertia[oB]];
    in.AOwnerFamily = ow.family[oA];
    in.BOwnerFamily = ow.family[oB];
    in.ALinVel = ow.vel[oA];
    // An image across a sheared cell's z face also moves at the shear velocity (Lees–Edwards).
    in.BLinVel = ow.vel[oB] + imageVelocity(s.frame.periodic, shiftB);
    in.ARotVel = ow.angVel[oA];
    in.BRotVel = ow.angVel[oB];
    in.AOwner = oA;
    in.BOwner = oB;
    in.AGeo = a;
    in.BGeo = b;
}

template <class S>
DEME_HD_INLINE void gatherContactInputsOfType(const S& s, size_t c, uint8_t type, float time, float ts,
                                              ContactInputs& in) {
    gatherContactInputsOfType(s, pairAOf(s, c), s.contacts.geomB[c], type, time, ts, in);
}

template <class S>
DEME_HD_INLINE void gatherContactInputs(const S& s, size_t c, float time, float ts, ContactInputs& in) {
    gatherContactInputsOfType(s, c, contactTypeAt(s, c), time, ts, in);
}

}  // namespace deme
