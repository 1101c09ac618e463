// Sphere-triangle contacts on connected meshes: which of them count, so that a sphere touching a
// tessellated surface feels the force one smooth surface would give.
//
// The rule: a sphere's contact with triangle T counts if T's closest point to the sphere centre is
// a local minimum of the distance to the mesh surface, and T owns that point.
//  - A closest point inside T is a local minimum: it counts.
//  - A closest point on an edge or a vertex of T also lies on the triangles sharing that edge or
//    vertex. If one of them has a closer point, the distance still decreases across the edge: the
//    contact is not a local minimum and does not count (this removes the spurious edge contacts of
//    a flat floor's neighbouring triangles, at any triangle size). If they share the very same
//    closest point (a convex ridge, or a sphere exactly over a seam of a flat floor), the lowest
//    triangle id among them owns it: one contact, never a doubled one.
// Hence on a flat tessellated floor exactly one contact counts, with the normal and overlap of the
// plane, and nothing jumps when the sphere rolls across an edge; in a V-groove both faces count.
//
// History: when a sphere's counting contact moves from one triangle of a mesh to another, the new
// contact takes over the old one's wildcards (tangential displacement etc.), so friction is
// continuous across edges.
#pragma once

#include "runtime/SimState.h"

namespace deme {

// Updates contacts.meshState for every sphere-triangle contact (bit 0: counts now, bit 1: counted
// in the previous step) and hands history over. Runs before the force pass of each step.
void resolveMeshContacts(SimState& s);

}  // namespace deme
