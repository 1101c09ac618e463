// Sphere-triangle contacts on connected meshes: which of them count, so that a sphere touching a
// tessellated surface feels the force one smooth surface would give.
//
// The rule: a sphere's contact with triangle T counts if T's closest point to the sphere centre is
// a local minimum of the distance to the mesh surface, and no nearer contact of the same mesh has
// already taken that point.
//  - A closest point inside T is a local minimum.
//  - A closest point on an edge or a vertex of T also lies on the triangles sharing that edge or
//    vertex. If one of them is closer to the centre, the distance still decreases across the edge:
//    not a local minimum, so the contact does not count (this removes the spurious edge contacts of
//    a flat floor's neighbouring triangles, at any triangle size).
//  - Contacts of one sphere are taken nearest first (ties by triangle id); one whose point
//    coincides with a point already taken (a seam, a vertex, a convex ridge) does not count again:
//    one contact, never a doubled one.
// Hence on a flat tessellated floor exactly one contact counts, with the normal and overlap of the
// plane, and nothing jumps when the sphere rolls across an edge; in a V-groove both faces count.
//
// History: when a sphere's counting contact moves from one triangle of a mesh to another, the new
// contact takes over the old one's wildcards (tangential displacement etc.), so friction is
// continuous across edges.
#pragma once

#include "state/SimState.h"

namespace deme {

// Updates contacts.meshState for every sphere-triangle contact (bit 0: counts now, bit 1: counted
// in the previous step) and hands history over. Runs before the force pass of each step.
void resolveMeshContacts(SimState& s);

}  // namespace deme
