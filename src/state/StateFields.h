// The simulation state described once (docs/ARCHITECTURE.md): every array of the state is one line
// of a field list below, and the host arrays (state/SimState.h), the view kernels see
// (state/StateView.h) and the CUDA backend's device buffers with their copies
// (backend/cuda/DeviceState.h) are all made from these lists. Adding a field is one line here.
// Plain preprocessor and templates only: NVRTC compiles this header too.
//
// Each list entry is X(name, type, role); the role says who writes the field while steps run:
//   EVOLVES  the steps write it: after a run the device copy is the newer (uploaded and downloaded)
//   INPUT    only the host writes it (uploaded, never downloaded)
//   SCRATCH  the steps' own per-step results (sized where the steps run, never copied)
//   HOST     the CPU backend's own bookkeeping (never on a device)
//   RESULT   the steps write it, and only the steps and a few readers need it: a GPU run keeps it
//            on the device alone, the host fetching it when asked (a tracker's rows, a checkpoint,
//            a scene edit). Empty on the host means zero (an assembled scene has none; each
//            backend's upload makes them), so a GPU run's host never holds them for every owner.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {
// A slot of the CPU's force reduction (DEME_CONTACT_FIELDS): the forces on A of a block's contacts
// with one B owner, and minus their torques about it, summed (global frame); side by side, so that
// a contact's two sums are one cache line.
struct WindowLoad {
    float3 force, negTorque;
};
}  // namespace deme

// Owners (paper §2.4): clumps, then analytical objects, then meshes, in a space-filling-curve order.
#define DEME_OWNER_FIELDS(X)                                                                         \
    X(voxel, voxelID_t, EVOLVES)    /* compact position (§2.3): voxel index ... */                  \
    X(subX, subVoxelPos_t, EVOLVES) /* ... and sub-voxel offsets */                                  \
    X(subY, subVoxelPos_t, EVOLVES)                                                                  \
    X(subZ, subVoxelPos_t, EVOLVES)                                                                  \
    X(oriQ, oriQ_t, EVOLVES)                                                                         \
    X(vel, float3, EVOLVES)          /* global frame */                                              \
    X(angVel, float3, EVOLVES)       /* local (body) frame */                                        \
    X(family, family_t, EVOLVES)     /* ChangeFamilyWhen changes it on the device */                 \
    X(inertia, inertiaID_t, INPUT)   /* index into the mass properties (extent, dynamic) */          \
    X(contactForce, float3, RESULT)  /* contact force of the last step (global), for trackers */     \
    X(contactTorque, float3, RESULT) /* contact torque of the last step (global) */                  \
    /* Path length travelled since the snapshot of the contact set in use (the poses its          */ \
    /* detection saw): bounds how far every point of its geometry moved since. Set back at each   */ \
    /* installation, so it stays within about a margin and a float holds it to 1e-7 of that.     */  \
    X(travel, float, RESULT)

// Tracker loads (DEMTracker::AddAcc, AddAngAcc) for the coming DoDynamics call, per owner. They
// exist only from the first load to the end of the call that applies it, and are empty otherwise:
// most runs never add one, and two arrays of zeros would cost every owner 24 bytes.
#define DEME_TRACKER_LOAD_FIELDS(X) \
    X(extraAcc, float3, INPUT)      \
    X(extraAngAcc, float3, INPUT) /* owner frame */

// Mass properties, shared by owners of one template (a clump template, or one external object or
// mesh), with what else such owners share: the extent of their geometry (the largest distance from
// the owner centre to it: what bounds a point's travel from the owner's), and whether forces move
// them.
#define DEME_MASS_FIELDS(X)                                    \
    X(mass, float, INPUT)                                      \
    X(moi, float3, INPUT) /* principal moments, owner frame */ \
    X(extent, float, INPUT)                                    \
    X(dynamic, uint8_t, INPUT) /* 1: moved by forces (clumps, free meshes); 0: kinematic */

#define DEME_SPHERE_FIELDS(X)                                  \
    X(owner, bodyID_t, INPUT)                                  \
    X(relPos, float3, INPUT) /* centre in the owner's frame */ \
    X(radius, float, INPUT)                                    \
    X(material, materialID_t, INPUT)

#define DEME_ANALYTICAL_FIELDS(X)                                                  \
    X(owner, bodyID_t, INPUT)                                                      \
    X(type, uint8_t, INPUT)   /* AnalyticalType */                                 \
    X(relPos, float3, INPUT)  /* a point of the surface, owner frame */            \
    X(relDir, float3, INPUT)  /* plane normal (towards grains) or cylinder axis */ \
    X(radius, float, INPUT)   /* cylinder radius */                                \
    X(inside, uint8_t, INPUT) /* cylinder: 1 if grains live inside */              \
    X(material, materialID_t, INPUT)

// Mesh triangles. Vertices are welded by position within each mesh; vertTris lists, per welded
// vertex, the triangles that use it (from vertTriStart): the topology of the smooth-surface rule.
#define DEME_TRIANGLE_FIELDS(X)                                     \
    X(owner, bodyID_t, INPUT)                                       \
    X(v0, float3, INPUT) /* owner frame */                          \
    X(v1, float3, INPUT)                                            \
    X(v2, float3, INPUT)                                            \
    X(material, materialID_t, INPUT)                                \
    X(vert, uint32_t, INPUT) /* 3 welded vertex ids per triangle */ \
    X(vertTriStart, uint32_t, INPUT)                                \
    X(vertTris, uint32_t, INPUT)

// The active-contact set, sorted by key = (geomA << 32) | geomB with geometry ids in one space:
// spheres [0, nSpheres), analytical components [nSpheres, nSpheres + nAnalytical), then triangles.
// The CUDA backend keeps its contact sets itself (two, for history mapping): these lists give their
// fields too, and the host copy is its record between calls. A pair's type is not stored: it
// follows from B's place in the id space (state/ContactTypeOf.h).
#define DEME_CONTACT_FIELDS(X)                                                                          \
    X(geomA, bodyID_t, EVOLVES)                                                                         \
    X(geomB, bodyID_t, EVOLVES)                                                                         \
    X(wildcards, float, EVOLVES) /* numWildcards values per contact, contact-major */                   \
    /* 1: the pair stays in the set when detection no longer finds it, until the force model      */    \
    /* clears the flag or the user removes it (DEMSolver::MarkPersistentContact). The CPU's steps */    \
    /* keep none where no pair has it and the model sets none (every pair's is then 0).           */    \
    X(persistent, uint8_t, EVOLVES)                                                                     \
    /* Sphere-triangle contacts: bit 0 set if it counted this step, bit 1 if in the previous one   */   \
    /* (the CPU's set keeps none in a scene without triangles: every pair's is then 0).           */    \
    X(meshState, uint8_t, EVOLVES)                                                                      \
    X(force, float3, EVOLVES)            /* on A, global, of a storing step (ContactForceView.h) */     \
    X(meshContacts, uint32_t, HOST)      /* indices of the sphere-triangle contacts */                  \
    X(meshContactGroups, uint32_t, HOST) /* where each sphere's run in meshContacts starts, + end */    \
    /* The CPU's force reduction (backend/cpu/ForcePassLoop.h). The set is sorted by A, and A is  */    \
    /* always a sphere, so each owner's contacts as A are one run (ownerAStart), which the force  */    \
    /* pass adds to A's owner in contact order. B's share is summed per block of A's owners: a B  */    \
    /* owner in the block itself is summed by the block's thread and added to the owner at the    */    \
    /* block's end (ownerBInBlock); for the others each block has a window of slots, one per      */    \
    /* distinct such owner (blockWindowStart), each such contact its slot in the window, listed   */    \
    /* in contact order (outSlot from blockOutStart; a B owner is in A's block or not by its id), */    \
    /* and the reduction adds an owner's slots in block order (ownerBStart, ownerBSlots). So no   */    \
    /* load is stored per contact, and a slot only per contact that crosses a block (a quarter).  */    \
    X(ownerAStart, uint32_t, HOST)      /* contacts [ownerAStart[o], ownerAStart[o + 1]) have A in o */ \
    X(blockWindowStart, uint32_t, HOST) /* block k's slots: [blockWindowStart[k], ... [k + 1]) */       \
    X(blockOutStart, uint32_t, HOST)    /* block k's crossing contacts' slots from outSlot[this] */     \
    X(outSlot, uint16_t, HOST)          /* per crossing contact, its window slot; empty where ... */    \
    X(outSlotWide, uint32_t, HOST)      /* ... a window has over 65,535 slots, and this is used */      \
    X(window, WindowLoad, HOST)         /* per slot: B's owner's loads from the block's contacts */     \
    X(ownerBStart, uint32_t, HOST)      /* owner o takes slots ownerBSlots[ownerBStart[o] ..] as B */   \
    X(ownerBSlots, uint32_t, HOST)                                                                      \
    X(ownerBInBlock, uint64_t, HOST) /* bit o: owner o is B of a contact of its own block */

// Quantities derived from the owner state, refreshed after every integration step (and after any
// host-side edit) so that the force pass and contact detection read them instead of recomputing
// them for every contact: the placed geometry. (An owner's position and global spin are not among
// them: their readers decode the compact position, state/OwnerCentre.h, and turn the owner-frame
// spin with the orientation they read anyway, dynamics/ContactInputsGather.h.)
#define DEME_CACHE_FIELDS(X)                                                     \
    X(spherePos, double3, EVOLVES) /* sphere centres */                          \
    X(sphereArm, float3, EVOLVES)  /* sphere centre minus owner centre */        \
    X(analPos, double3, EVOLVES)   /* analytical components' reference points */ \
    X(analDir, double3, EVOLVES)   /* analytical normals / axes (unit) */        \
    X(triVert, double3, EVOLVES)   /* 3 global vertices per triangle */

// Per-owner results of the integration sweep that later sweeps of the same step read.
#define DEME_SCRATCH_FIELDS(X) X(flags, uint8_t, SCRATCH) /* OwnerStepFlag bits */

namespace deme {

// Who writes a field while steps run (see above).
enum class FieldRole { EVOLVES, INPUT, SCRATCH, HOST, RESULT };

// One struct template per group, holding each field in storage A<T>: std::vector<T> on the host,
// T* in the view, a device buffer on the GPU.
#define DEME_DECLARE_FIELD(name, T, role) A<T> name;
template <template <class> class A>
struct OwnerFields {
    DEME_OWNER_FIELDS(DEME_DECLARE_FIELD)
};
template <template <class> class A>
struct TrackerLoadFields {
    DEME_TRACKER_LOAD_FIELDS(DEME_DECLARE_FIELD)
};
template <template <class> class A>
struct MassFields {
    DEME_MASS_FIELDS(DEME_DECLARE_FIELD)
};
template <template <class> class A>
struct SphereFields {
    DEME_SPHERE_FIELDS(DEME_DECLARE_FIELD)
};
template <template <class> class A>
struct AnalyticalFields {
    DEME_ANALYTICAL_FIELDS(DEME_DECLARE_FIELD)
};
template <template <class> class A>
struct TriangleFields {
    DEME_TRIANGLE_FIELDS(DEME_DECLARE_FIELD)
};
template <template <class> class A>
struct ContactFields {
    DEME_CONTACT_FIELDS(DEME_DECLARE_FIELD)
};
template <template <class> class A>
struct CacheFields {
    DEME_CACHE_FIELDS(DEME_DECLARE_FIELD)
};
template <template <class> class A>
struct ScratchFields {
    DEME_SCRATCH_FIELDS(DEME_DECLARE_FIELD)
};
#undef DEME_DECLARE_FIELD

// forEach<Group>Field(a, b, f): f(a.field, b.field, role) for every field of the group, in list
// order, over two storages of the same group (e.g. host arrays and device buffers).
#define DEME_VISIT_FIELD(name, T, role) f(a.name, b.name, FieldRole::role);
#define DEME_FIELD_VISITOR(Group, LIST)                      \
    template <class GA, class GB, class F>                   \
    inline void forEach##Group##Field(GA& a, GB& b, F&& f) { \
        LIST(DEME_VISIT_FIELD)                               \
    }
DEME_FIELD_VISITOR(Owner, DEME_OWNER_FIELDS)
DEME_FIELD_VISITOR(TrackerLoad, DEME_TRACKER_LOAD_FIELDS)
DEME_FIELD_VISITOR(Mass, DEME_MASS_FIELDS)
DEME_FIELD_VISITOR(Sphere, DEME_SPHERE_FIELDS)
DEME_FIELD_VISITOR(Analytical, DEME_ANALYTICAL_FIELDS)
DEME_FIELD_VISITOR(Triangle, DEME_TRIANGLE_FIELDS)
DEME_FIELD_VISITOR(Contact, DEME_CONTACT_FIELDS)
DEME_FIELD_VISITOR(Cache, DEME_CACHE_FIELDS)
DEME_FIELD_VISITOR(Scratch, DEME_SCRATCH_FIELDS)
#undef DEME_FIELD_VISITOR
#undef DEME_VISIT_FIELD

// Every group of a state, in one call: f(a.group, b.group, visitor) where visitor is the group's
// forEach<Group>Field (so that code over all groups is written once too).
#define DEME_STATE_GROUPS(G)  \
    G(owners, Owner)          \
    G(massProps, Mass)        \
    G(spheres, Sphere)        \
    G(analytical, Analytical) \
    G(triangles, Triangle)    \
    G(cache, Cache)           \
    G(integrationScratch, Scratch)

}  // namespace deme
