// The GPU force pass as a template over the contact force model, the device twin of
// backend/cpu/ForcePassLoop.h: for every contact of the set, gather the model's inputs, run the model,
// add the force and the torques about both owners to the owners' loads, and store the force on A
// where the view asks for it (ContactView::force).
// Dynamics.cu instantiates it for the built-in models; the code generated for a user's model
// (forcemodel/CudaCodeGen.cpp) instantiates it for that model. The rules are the CPU loop's:
//   - a model that does not see apart pairs gets no call for them: zero force, wildcards cleared;
//     sphere pairs are told apart from their centres alone (no gather);
//   - a model that sees apart pairs (custom models) is called for every pair whose geometry counts,
//     touching or not, and its force is applied either way (a long-range law acts at a distance);
//   - sphere-triangle contacts the mesh rule did not count this step (meshState bit 0) get no call;
//   - a model that writes `persistent` gets the contact's flag and its value is stored back.
// Loads on the few non-clump owners (walls, meshes) are first summed per block in shared memory:
// every contact of a floor lands on one owner, and per-contact atomics on one address serialise.
#pragma once

#include "backend/cuda/kernels/KernelArgs.cuh"
#include "dynamics/ContactInputsGather.h"
#include "state/StateView.h"

namespace deme {
namespace force_pass_detail {

__device__ inline void atomicAdd3(float3* target, const float3& v) {
    atomicAdd(&target->x, v.x);
    atomicAdd(&target->y, v.y);
    atomicAdd(&target->z, v.z);
}

}  // namespace force_pass_detail

// The body of a force-pass kernel: one thread per contact, blocks of any size.
template <class Model>
__device__ inline void forcePassKernel(const StateView& s, const Model& model, float time, float dt,
                                       unsigned int firstNonClump, unsigned int numNonClump, StepReduction* red) {
    using force_pass_detail::atomicAdd3;
    __shared__ float3 blockForce[SHARED_LOAD_SLOTS], blockTorque[SHARED_LOAD_SLOTS];
    __shared__ unsigned int blockReal, blockSS;
    const unsigned int slots = numNonClump < SHARED_LOAD_SLOTS ? numNonClump : SHARED_LOAD_SLOTS;
    for (unsigned int k = threadIdx.x; k < slots; k += blockDim.x) {
        blockForce[k] = make_float3(0.f);
        blockTorque[k] = make_float3(0.f);
    }
    if (threadIdx.x == 0) blockReal = blockSS = 0;
    __syncthreads();

    const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (i < s.numContacts) {
        const ContactView& c = s.contacts;
        // The wildcard count is a constant of the model, so history loops unroll.
        constexpr unsigned int W = Model::kNumContactWildcards;
        float* wc = c.wildcards + i * W;
        const uint8_t type = c.type[i];
        ContactInputs in;
        bool gather = type != SPHERE_TRIANGLE || (c.meshState[i] & 1u);
        if (type == SPHERE_SPHERE && !Model::kSeesApartPairs) {
            // Most pairs of the set that are apart are sphere pairs: tell them from the centres.
            const double3 d = s.cache.spherePos[c.geomA[i]] - s.cache.spherePos[c.geomB[i]];
            const double reach = (double)s.spheres.radius[c.geomA[i]] + (double)s.spheres.radius[c.geomB[i]];
            gather = dot(d, d) < reach * reach;
        }
        if (gather) gatherContactInputsOfType(s, i, type, time, dt, in);
        // The quick sphere test above is the built-in models' whole decision for sphere pairs.
        const bool touching =
            gather && (type == SPHERE_SPHERE && !Model::kSeesApartPairs ? true : in.overlapDepth > 0.0);
        if (!(Model::kSeesApartPairs ? gather : touching)) {
            // No call: no force, and the contact's history ends.
            for (unsigned int w = 0; w < W; w++) wc[w] = 0.f;
            if (c.force) c.force[i] = make_float3(0.f);
        } else {
            float3 force = make_float3(0.f), torque_only_force = make_float3(0.f);
            bool persistent = Model::kWritesPersistent && c.persistent[i] != 0;
            model(in, wc, force, torque_only_force, persistent);
            if (Model::kWritesPersistent) c.persistent[i] = persistent ? 1 : 0;
            const float3 total = force + torque_only_force;
            const float3 tA = cross(in.armA, total), tB = cross(in.armB, -total);
            if (c.force) c.force[i] = force;
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
            if (touching) {
                atomicAdd(&blockReal, 1u);
                if (type == SPHERE_SPHERE) atomicAdd(&blockSS, 1u);
            }
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

}  // namespace deme
