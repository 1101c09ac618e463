// The dynamics side on the GPU: mesh contact rule, force pass with load accumulation, integration
// and pose caches. Compiled at run time by NVRTC together with the physics headers; every per-item
// function here is the one the CPU sweeps call.
#include "backend/cuda/kernels/KernelArgs.cuh"
#include "dynamics/ContactInputsGather.h"
#include "dynamics/MeshContactRule.h"
#include "dynamics/OwnerStep.h"
#include "physics/BuiltInForceModels.h"
#include "runtime/StateView.h"

namespace deme {

namespace {

__device__ inline size_t globalIndex() { return (size_t)blockIdx.x * blockDim.x + threadIdx.x; }

__device__ inline void atomicAdd3(float3* target, const float3& v) {
    atomicAdd(&target->x, v.x);
    atomicAdd(&target->y, v.y);
    atomicAdd(&target->z, v.z);
}

__device__ inline void raiseError(StepReduction* red, unsigned int flag, unsigned int item) {
    if (atomicOr(&red->errorFlags, flag) == 0u) red->errorItem = item;
}

}  // namespace

extern "C" __global__ void deme_reset_reduction(StepReduction* red) {
    if (globalIndex() != 0) return;
    red->maxTravelBits = 0ull;
    red->maxSpeedBits = 0u;
    red->firstFault = 0xFFFFFFFFu;
    red->anyLargeRotation = 0u;
    red->errorFlags = 0u;
    red->errorItem = 0u;
    red->realContacts = red->realSphereSphere = 0ull;
}

extern "C" __global__ void deme_copy_doubles(double* dst, const double* src, unsigned int n) {
    const size_t i = globalIndex();
    if (i < n) dst[i] = src[i];
}

extern "C" __global__ void deme_clear_owner_loads(StateView s) {
    const size_t o = globalIndex();
    if (o >= s.numOwners) return;
    s.owners.contactForce[o] = make_float3(0.f);
    s.owners.contactTorque[o] = make_float3(0.f);
}

// One thread per sphere-triangle contact that opens its sphere's run (contacts are sorted by
// sphere, a sphere's triangle contacts last).
extern "C" __global__ void deme_resolve_mesh_contacts(StateView s, StepReduction* red) {
    const size_t i = globalIndex();
    const ContactView& c = s.contacts;
    if (i >= s.numContacts || c.type[i] != SPHERE_TRIANGLE) return;
    if (i > 0 && c.type[i - 1] == SPHERE_TRIANGLE && c.geomA[i - 1] == c.geomA[i]) return;
    size_t n = 1;
    while (i + n < s.numContacts && c.type[i + n] == SPHERE_TRIANGLE && c.geomA[i + n] == c.geomA[i]) n++;
    MeshCandidate cand[MAX_MESH_CANDIDATES];
    if (!resolveSphereMeshContacts(s, i, n, cand, MAX_MESH_CANDIDATES))
        raiseError(red, KERNEL_ERROR_MESH_CANDIDATES, c.geomA[i]);
}

// Force pass: each contact's force and torques (as on the CPU), added to both owners' loads. Loads
// on the few non-clump owners (walls, meshes) are first summed per block in shared memory.
extern "C" __global__ void deme_force_pass(StateView s, float time, float dt, FrictionalHertzModel model,
                                           unsigned int firstNonClump, unsigned int numNonClump, StepReduction* red) {
    __shared__ float3 blockForce[SHARED_LOAD_SLOTS], blockTorque[SHARED_LOAD_SLOTS];
    __shared__ unsigned int blockReal, blockSS;
    const unsigned int slots = numNonClump < SHARED_LOAD_SLOTS ? numNonClump : SHARED_LOAD_SLOTS;
    for (unsigned int k = threadIdx.x; k < slots; k += blockDim.x) {
        blockForce[k] = make_float3(0.f);
        blockTorque[k] = make_float3(0.f);
    }
    if (threadIdx.x == 0) blockReal = blockSS = 0;
    __syncthreads();

    const size_t i = globalIndex();
    if (i < s.numContacts) {
        ContactView& c = s.contacts;
        constexpr unsigned int W = FrictionalHertzModel::kNumContactWildcards;
        float* wc = c.wildcards + i * W;
        const uint8_t type = c.type[i];
        bool touching;
        ContactInputs in;
        if (type == SPHERE_SPHERE) {
            const double3 d = s.cache.spherePos[c.geomA[i]] - s.cache.spherePos[c.geomB[i]];
            const double reach = (double)s.spheres.radius[c.geomA[i]] + (double)s.spheres.radius[c.geomB[i]];
            touching = dot(d, d) < reach * reach;
            if (touching) gatherContactInputsOfType(s, i, SPHERE_SPHERE, time, dt, in);
        } else {
            gatherContactInputsOfType(s, i, type, time, dt, in);
            touching = in.overlapDepth > 0.0 && (type != SPHERE_TRIANGLE || (c.meshState[i] & 1u));
        }
        if (!touching) {
            for (unsigned int w = 0; w < W; w++) wc[w] = 0.f;
            c.force[i] = c.torqueA[i] = c.torqueB[i] = make_float3(0.f);
        } else {
            float3 force = make_float3(0.f), torque_only_force = make_float3(0.f);
            bool persistent = false;
            model(in, wc, force, torque_only_force, persistent);
            const float3 total = force + torque_only_force;
            const float3 tA = cross(in.armA, total), tB = cross(in.armB, -total);
            c.force[i] = force;
            c.torqueA[i] = tA;
            c.torqueB[i] = tB;
            atomicAdd3(&s.owners.contactForce[in.AOwner], force);
            atomicAdd3(&s.owners.contactTorque[in.AOwner], tA);
            const unsigned int slot = in.BOwner - firstNonClump;
            if (in.BOwner >= firstNonClump && slot < slots) {
                atomicAdd3(&blockForce[slot], -force);
                atomicAdd3(&blockTorque[slot], tB);
            } else {
                atomicAdd3(&s.owners.contactForce[in.BOwner], -force);
                atomicAdd3(&s.owners.contactTorque[in.BOwner], tB);
            }
            atomicAdd(&blockReal, 1u);
            if (type == SPHERE_SPHERE) atomicAdd(&blockSS, 1u);
        }
    }
    __syncthreads();
    for (unsigned int k = threadIdx.x; k < slots; k += blockDim.x) {
        const float3 f = blockForce[k], t = blockTorque[k];
        if (f.x != 0.f || f.y != 0.f || f.z != 0.f) atomicAdd3(&s.owners.contactForce[firstNonClump + k], f);
        if (t.x != 0.f || t.y != 0.f || t.z != 0.f) atomicAdd3(&s.owners.contactTorque[firstNonClump + k], t);
    }
    if (threadIdx.x == 0) {
        if (blockReal) atomicAdd(&red->realContacts, (unsigned long long)blockReal);
        if (blockSS) atomicAdd(&red->realSphereSphere, (unsigned long long)blockSS);
    }
}

// Integration of every owner (stepOwner), with the step's maxima and first fault combined per warp.
extern "C" __global__ void deme_integrate(StateView s, const FamilyStepMotion* motion, StepConstants consts,
                                          const double* travelBaseline, StepReduction* red) {
    const size_t o = globalIndex();
    double travel = 0.0;
    float speed = 0.f;
    unsigned int fault = 0xFFFFFFFFu, large = 0u;
    if (o < s.numOwners) {
        const OwnerStepResult r = stepOwner(s, o, motion[s.owners.family[o]], consts, travelBaseline[o]);
        s.integrationScratch.flags[o] = r.flags;
        travel = r.travelSinceDetection > 0.0 ? r.travelSinceDetection : 0.0;
        speed = r.speed;
        if (r.flags & STEP_FAULTS) fault = (unsigned int)o;
        large = (r.flags & STEP_LARGE_ROTATION) ? 1u : 0u;
    }
    for (int off = 16; off > 0; off >>= 1) {
        travel = fmax(travel, __shfl_down_sync(0xFFFFFFFFu, travel, off));
        speed = fmaxf(speed, __shfl_down_sync(0xFFFFFFFFu, speed, off));
        fault = min(fault, __shfl_down_sync(0xFFFFFFFFu, fault, off));
        large |= __shfl_down_sync(0xFFFFFFFFu, large, off);
    }
    if ((threadIdx.x & 31u) == 0u) {
        if (travel > 0.0) atomicMax(&red->maxTravelBits, (unsigned long long)__double_as_longlong(travel));
        if (speed > 0.f) atomicMax(&red->maxSpeedBits, __float_as_uint(speed));
        if (fault != 0xFFFFFFFFu) atomicMin(&red->firstFault, fault);
        if (large) red->anyLargeRotation = 1u;
    }
}

// Owners whose rotation this step was too large for the series step: exact step (rare).
extern "C" __global__ void deme_large_rotations(StateView s, float h) {
    const size_t o = globalIndex();
    if (o >= s.numOwners || !(s.integrationScratch.flags[o] & STEP_LARGE_ROTATION)) return;
    s.owners.oriQ[o] = integrateOrientation(s.owners.oriQ[o], s.integrationScratch.midAngVel[o], h);
    s.cache.ownerAngVelGlobal[o] = rotateToGlobal(s.owners.oriQ[o], s.owners.angVel[o]);
}

extern "C" __global__ void deme_place_spheres(StateView s) {
    const size_t i = globalIndex();
    if (i < s.numSpheres) placeSphere(s, i);
}

extern "C" __global__ void deme_place_triangles(StateView s) {
    const size_t t = globalIndex();
    if (t < s.numTriangles && (s.integrationScratch.flags[s.triangles.owner[t]] & STEP_MOVED)) placeTriangle(s, t);
}

// Analytical owners (few): cached components, and travel bounded by the fastest surface point.
// One thread per analytical owner.
extern "C" __global__ void deme_analytical_step(StateView s, unsigned int firstOwner, unsigned int numOwners, float h,
                                                double domainDiagonal, const double* travelBaseline,
                                                StepReduction* red) {
    const size_t j = globalIndex();
    if (j >= numOwners) return;
    const unsigned int o = firstOwner + (unsigned int)j;
    float rate = 0.f;
    for (unsigned int k = 0; k < s.numAnalytical; k++) {
        if (s.analytical.owner[k] != o) continue;
        placeAnalytical(s, k);
        rate = fmaxf(rate, analyticalSurfaceSpeed(s, k, domainDiagonal));
    }
    s.owners.travel[o] += (double)(rate * h);
    const double since = s.owners.travel[o] - travelBaseline[o];
    if (since > 0.0) atomicMax(&red->maxTravelBits, (unsigned long long)__double_as_longlong(since));
    if (rate > 0.f) atomicMax(&red->maxSpeedBits, __float_as_uint(rate));
}

}  // namespace deme
