// The simulation state as flat arrays behind raw pointers: what GPU kernels get. Its members carry
// the names of SimState's, so the per-item code (contact inputs, owner step, force models) is written
// once as templates over the state type and runs on SimState on the CPU and on a StateView of device
// memory on the GPU. Plain data only, so NVRTC can compile it.
#pragma once

#include <deme/VariableTypes.h>

#include "physics/CompactPosition.h"

namespace deme {

struct OwnerView {
    voxelID_t* voxel;
    subVoxelPos_t *subX, *subY, *subZ;
    oriQ_t* oriQ;
    float3 *vel, *angVel;
    family_t* family;
    uint8_t *type, *dynamic;
    inertiaID_t* inertia;
    float* extent;
    float3 *contactForce, *contactTorque, *extraAcc, *extraAngAcc;
    double* travel;
};

struct MassView {
    float* mass;
    float3* moi;
};

struct SphereView {
    bodyID_t* owner;
    float3* relPos;
    float* radius;
    materialID_t* material;
};

struct AnalyticalView {
    bodyID_t* owner;
    uint8_t* type;
    float3 *relPos, *relDir;
    float* radius;
    uint8_t* inside;
    materialID_t* material;
};

struct TriangleView {
    bodyID_t* owner;
    float3 *v0, *v1, *v2;
    materialID_t* material;
    uint32_t* vert;
    uint32_t *vertTriStart, *vertTris;
};

struct ContactView {
    bodyID_t *geomA, *geomB;
    uint8_t* type;
    float* wildcards;
    uint8_t* meshState;
    // Force on A per contact, for the host's contact output. Null in the steps whose forces nobody
    // reads (all but the last of a DoDynamics call): the GPU adds loads to the owners directly, so
    // per-contact forces and torques are not otherwise needed, and not writing them saves a third
    // of the force pass's memory traffic.
    float3* force;
    uint8_t* persistent;  // ContactArrays::persistent; read and written by models that write it
};

struct CacheView {
    double3* ownerPos;
    float3* ownerAngVelGlobal;
    double3* spherePos;
    float3* sphereArm;
    double3 *analPos, *analDir, *triVert;
};

struct IntegrationScratchView {
    uint8_t* flags;
    float3* midAngVel;
};

struct StateView {
    DomainFrame frame;
    double3 domainSize;
    OwnerView owners;
    MassView massProps;
    SphereView spheres;
    AnalyticalView analytical;
    TriangleView triangles;
    ContactView contacts;
    CacheView cache;
    IntegrationScratchView integrationScratch;
    unsigned int numWildcards;
    uint32_t numOwners, numSpheres, numAnalytical, numTriangles, numContacts;
    DEME_HD bodyID_t analyticalIdBase() const { return numSpheres; }
    DEME_HD bodyID_t triangleIdBase() const { return numSpheres + numAnalytical; }
};

}  // namespace deme
