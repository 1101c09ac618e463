// The simulation's flat structure-of-arrays state, built once at Initialize() (paper §2.3, §2.4).
// Owners carry mass, pose, velocity and family; geometries (spheres, analytical components) carry
// shape and material and point at their owner. Contacts are between geometries.
#pragma once

#include <vector>

#include <deme/VariableTypes.h>

#include "physics/CompactPosition.h"

namespace deme {

struct OwnerArrays {
    std::vector<voxelID_t> voxel;
    std::vector<subVoxelPos_t> subX, subY, subZ;
    std::vector<oriQ_t> oriQ;
    std::vector<float3> vel;     // global
    std::vector<float3> angVel;  // local (body) frame
    std::vector<family_t> family;
    std::vector<uint8_t> type;         // OwnerType
    std::vector<uint8_t> dynamic;      // 1: moved by forces (clumps, free meshes); 0: kinematic
    std::vector<inertiaID_t> inertia;  // index into MassProperties
    std::vector<float> extent;         // largest distance from the owner centre to any point of its spheres
    // Results of the last step, for trackers and inspectors: contact force and torque (global).
    std::vector<float3> contactForce, contactTorque;
    // Extra acceleration added by trackers (AddAcc), applied during the next DoDynamics call.
    std::vector<float3> extraAcc, extraAngAcc;
    // Path length travelled since the start (an upper bound for every point of its geometry); the
    // travel since a contact detection is the difference to a snapshot taken then.
    std::vector<double> travel;

    size_t size() const { return voxel.size(); }
};

struct MassProperties {
    std::vector<float> mass;
    std::vector<float3> moi;  // principal moments, in the owner's local frame
};

struct SphereArrays {
    std::vector<bodyID_t> owner;
    std::vector<float3> relPos;  // centre in the owner's local frame
    std::vector<float> radius;
    std::vector<materialID_t> material;
    size_t size() const { return owner.size(); }
};

struct AnalyticalArrays {
    std::vector<bodyID_t> owner;
    std::vector<uint8_t> type;    // AnalyticalType
    std::vector<float3> relPos;   // a point of the surface, owner frame
    std::vector<float3> relDir;   // plane normal (towards grains) or cylinder axis, owner frame
    std::vector<float> radius;    // cylinder radius
    std::vector<uint8_t> inside;  // cylinder: 1 if grains live inside
    std::vector<materialID_t> material;
    size_t size() const { return owner.size(); }
};

// Mesh triangles. Vertices are welded by position within each mesh; `vertTris` lists, per welded
// vertex, the triangles that use it (the topology the smooth-surface contact rule needs).
struct TriangleArrays {
    std::vector<bodyID_t> owner;
    std::vector<float3> v0, v1, v2;  // owner frame
    std::vector<materialID_t> material;
    std::vector<uint32_t> vert;  // 3 welded vertex ids per triangle
    std::vector<uint32_t> vertTriStart, vertTris;
    size_t size() const { return owner.size(); }
};

// The active-contact set. Sorted by key = (geomA << 32) | geomB with geometry ids in one space:
// spheres [0, nSpheres), analytical components [nSpheres, nSpheres + nAnalytical), then triangles.
struct ContactArrays {
    std::vector<bodyID_t> geomA, geomB;
    std::vector<uint8_t> type;     // ContactType
    std::vector<float> wildcards;  // numWildcards values per contact, contact-major
    // 1: the pair stays in the set even when detection no longer finds it, until the force model
    // clears the flag or the user removes it (DEMSolver::MarkPersistentContact).
    std::vector<uint8_t> persistent;
    // Sphere-triangle contacts: bit 0 set if the contact counted this step, bit 1 if it did in the
    // previous step (see dynamics/MeshContacts.h).
    std::vector<uint8_t> meshState;
    std::vector<uint32_t> meshContacts;       // indices of the sphere-triangle contacts
    std::vector<uint32_t> meshContactGroups;  // where each sphere's run in meshContacts starts, plus the end
    // Results of the force pass.
    std::vector<float3> force;             // on A, global
    std::vector<float3> torqueA, torqueB;  // about each owner's centre, global
    // For force reduction: for each owner the contacts it takes part in, as (contact << 1) | isB.
    std::vector<uint32_t> ownerStart, ownerEntries;
    size_t size() const { return geomA.size(); }
};

inline uint64_t contactKey(bodyID_t a, bodyID_t b) { return (uint64_t(a) << 32) | uint64_t(b); }

// Quantities derived from the owner state, refreshed after every integration step (and after any
// host-side edit) so that the force pass and contact detection read them instead of recomputing
// them for every contact.
struct KinematicCache {
    std::vector<double3> ownerPos;  // decoded owner positions
    std::vector<float3> ownerAngVelGlobal;
    std::vector<double3> spherePos;  // sphere centres
    std::vector<float3> sphereArm;   // sphere centre minus owner centre
    std::vector<double3> analPos;    // analytical component reference points
    std::vector<double3> analDir;    // analytical normals / axes (unit)
    std::vector<double3> triVert;    // 3 global vertices per triangle
};

// Per-owner results of the integration sweep that later sweeps of the same step read.
struct IntegrationScratch {
    std::vector<uint8_t> flags;       // OwnerStepFlag bits
    std::vector<float3> midAngVel;    // midpoint angular velocity, kept only for large rotations
};

// Material property tables for the force model.
struct MaterialTables {
    unsigned int count = 0;
    // The standard properties, which the built-in models and the derived tables read (0 where a
    // material lacks one).
    std::vector<float> E, nu;         // per material
    std::vector<float> CoR, mu, Crr;  // per pair, count x count
    // Derived once per pair (MaterialMixing.h) so that force models need not mix per contact:
    // effective Young's and shear moduli, and the damping term of CoR.
    std::vector<float> E_eff, G_eff, beta_CoR;
    // Every property by name for a user's model, in the order of the model's layout
    // (forcemodel/ModelLayout.h): per-material ones, then the ones the model reads per pair.
    std::vector<std::vector<float>> props, pairProps;
};

// The force model's owner and geometry wildcards (paper Table 3): one array per wildcard, in the
// order the model declares them, indexed by internal owner id or unified geometry id. Contact
// wildcards live with the contacts (ContactArrays::wildcards).
struct WildcardArrays {
    std::vector<std::vector<float>> owner, geometry;
    // Contacts that appear between families a and b (either way round) start with `value` in
    // contact wildcard `index` instead of 0.
    struct ContactInit {
        family_t a, b;
        unsigned int index;
        float value;
    };
    std::vector<ContactInit> contactInit;
};

struct SimState {
    DomainFrame frame;
    double3 domainSize;
    OwnerArrays owners;
    MassProperties massProps;
    SphereArrays spheres;
    AnalyticalArrays analytical;
    TriangleArrays triangles;
    ContactArrays contacts;
    KinematicCache cache;
    IntegrationScratch integrationScratch;
    std::vector<uint32_t> ownerSphereStart;  // spheres of owner o: [start[o], start[o+1])
    std::vector<uint32_t> ownerTriStart;     // triangles of owner o: [start[o], start[o+1])
    // Owners and spheres are stored in a space-filling-curve order for memory locality; users see
    // ids in the order they added things (clumps batch by batch, then external objects).
    std::vector<bodyID_t> ownerUserToInternal, ownerInternalToUser;
    std::vector<bodyID_t> sphereInternalToUser, sphereUserToInternal;
    MaterialTables materials;
    WildcardArrays wildcards;
    unsigned int numWildcards = 0;
    size_t numClumps = 0;  // owners [0, numClumps) are clumps; analytical owners, then meshes follow
    size_t numAnalyticalOwners = 0;
    bool hasTrackerLoads = false;  // some owner has extraAcc/extraAngAcc for the coming call
    // First geometry id of each kind in the unified id space of contacts.
    bodyID_t analyticalIdBase() const { return (bodyID_t)spheres.size(); }
    bodyID_t triangleIdBase() const { return (bodyID_t)(spheres.size() + analytical.size()); }
};

}  // namespace deme
