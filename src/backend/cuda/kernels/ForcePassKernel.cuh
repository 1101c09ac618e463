// The GPU's force pass as a template over the contact force model: one thread per contact of the
// set takes the per-contact step of dynamics/ContactStep.h (where the rules are), adds the force and
// the torques about both owners to the owners' loads with atomics, and stores the force on A where
// the view asks for it (ContactView::force). Dynamics.cu instantiates it for the built-in models; the
// code generated for a user's model (forcemodel/CudaCodeGen.cpp) instantiates it for that model.
// Loads on the few non-clump owners (walls, meshes) are first summed per block in shared memory:
// every contact of a floor lands on one owner, and per-contact atomics on one address serialise.
#pragma once

#include "backend/cuda/kernels/DependentLaunch.cuh"
#include "backend/cuda/kernels/KernelArgs.cuh"
#include "dynamics/ContactStep.h"
#include "dynamics/PooledContactStep.h"
#include "state/StateView.h"

namespace deme {
namespace force_pass_detail {

// How an owner's float3 load in global memory is added to (sm_90 and later; older GPUs take 0):
// 0: its three components one by one (three requests to L2);
// 1: the pair of components that starts on an 8-byte boundary as one vector reduction (red.v2.f32),
//    the third alone (owner o's float3 at 12 o bytes: x and y paired for even o, y and z for odd);
// 2 (default): where the float3 shares a 16-byte line's chunk with one float of a neighbour (owners
//    4k and 4k + 3 of an aligned array), one red.v4.f32 that adds +0 to the neighbour's float; the
//    others as in 1. +0 leaves every owner's sum as it is (a sum starts at +0 and so is never -0,
//    the one value that adding +0 changes), so each component gets exactly the additions it got.
// Timed on one H100 (BENCHMARKS.md, SMALL-SYSTEMS): the atomics are a large part of a lab-scale
// step. DEME_CUDA_DEFINES="DEME_VECTOR_ATOMICS=0" (or 1) times the others.
#ifndef DEME_VECTOR_ATOMICS
#define DEME_VECTOR_ATOMICS 2
#endif

// Adds v to the float3 at `target`, component by component (shared or global memory).
__device__ inline void atomicAdd3(float3* target, const float3& v) {
    atomicAdd(&target->x, v.x);
    atomicAdd(&target->y, v.y);
    atomicAdd(&target->z, v.z);
}

#if DEME_VECTOR_ATOMICS && defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
// Adds (a, b) to the two floats at p (8-byte aligned, global memory) in one reduction.
__device__ inline void reduceAdd2(float* p, float a, float b) {
    asm volatile("red.global.add.v2.f32 [%0], {%1, %2};" ::"l"(p), "f"(a), "f"(b) : "memory");
}

// Adds (a, b, c, d) to the four floats at p (16-byte aligned, global memory) in one reduction.
__device__ inline void reduceAdd4(float* p, float a, float b, float c, float d) {
    asm volatile("red.global.add.v4.f32 [%0], {%1, %2, %3, %4};" ::"l"(p), "f"(a), "f"(b), "f"(c), "f"(d)
                 : "memory");
}

// Adds v to loads[o] of an array of n float3s in global memory (DEME_VECTOR_ATOMICS above).
__device__ inline void atomicAddLoad(float3* loads, size_t o, size_t n, const float3& v) {
    float* p = &loads[o].x;
    const size_t at = reinterpret_cast<size_t>(p) & 15u;
    if (DEME_VECTOR_ATOMICS >= 2 && at == 0 && o + 1 < n) {
        reduceAdd4(p, v.x, v.y, v.z, 0.f);  // + 0 to owner o + 1's x
        return;
    }
    if (DEME_VECTOR_ATOMICS >= 2 && at == 4 && o > 0) {
        reduceAdd4(p - 1, 0.f, v.x, v.y, v.z);  // + 0 to owner o - 1's z
        return;
    }
    if ((at & 7u) == 0) {
        reduceAdd2(p, v.x, v.y);
        atomicAdd(p + 2, v.z);
    } else {
        atomicAdd(p, v.x);
        reduceAdd2(p + 1, v.y, v.z);
    }
}
#else
__device__ inline void atomicAddLoad(float3* loads, size_t o, size_t, const float3& v) { atomicAdd3(&loads[o], v); }
#endif

// Whether every component of a contact's load is zero (of either sign).
__device__ inline bool isZeroLoad(const ContactLoad& l) {
    return isZero(l.force) && isZero(l.torqueA) && isZero(l.torqueB);
}

}  // namespace force_pass_detail

// The body of a force-pass kernel: one thread per contact, blocks of any size. The step's time and
// size come from the batch's control block (dynamics/StepBatch.h), which also says whether the batch
// has ended (then the pass does nothing).
// `NoTriangles`: the scene has no meshes, so that no contact is a sphere and a triangle and that
// branch of the per-contact step drops out (most of its registers: ptxas for sm_90 puts the pass at 70
// registers uncapped and 4 bytes spilled at 64, against 113 and 202 bytes spilled at 64).
// `Pooled`: the set keeps its history pooled (state/HistoryPool.h, dynamics/PooledContactStep.h);
// a launch while the pool's `filling` is set makes the pending pairs' histories and nothing else.
template <class Model, bool NoTriangles = false, bool Pooled = false>
__device__ inline void forcePassKernel(const StateView& s, const Model& model, const StepBatchControl* ctl,
                                       unsigned int firstNonClump, unsigned int numNonClump, StepReduction* red) {
    using force_pass_detail::atomicAdd3;
    using force_pass_detail::atomicAddLoad;
    using force_pass_detail::isZeroLoad;
    constexpr uint8_t kType = NoTriangles ? NO_TRIANGLE_CONTACT : ANY_CONTACT_TYPE;
    // The contact's ids are loaded before the wait (DependentLaunch.cuh): the kernel before (the last
    // step's integration, or this step's load clearing or mesh rule) does not write them -- no kernel
    // of a step does -- and the round trip overlaps that kernel's end instead of following the wait.
    // A is decoded after it (state/CompactPairA.h, PairAList::load): B, A's base and A's byte are
    // then one round trip.
    const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    bodyID_t b = 0u;
    PairALoaded a{0u, 0u};
    if (i < s.numContacts) {
        b = s.contacts.geomB[i];
        a = s.pairAs.load(i);
    }
    beginDependentKernel();
    const ContactIds ids =
        i < s.numContacts ? contactIdsOf<kType>(s, s.pairAs.decode(a, i), b) : ContactIds{0u, 0u, 0u};
    if constexpr (Pooled) {
        if (s.historyPool.control->filling) {  // between a paused step's pass and its integration
            if (i < s.numContacts) fillPendingHistory<Model, kType>(s, model, i, ids, (float)ctl->time, (float)ctl->dt);
            return;
        }
    }
    if (ctl->stop) return;  // the same for every thread: no barrier is left waiting
    const float time = (float)ctl->time, dt = (float)ctl->dt;
    __shared__ float3 blockForce[SHARED_LOAD_SLOTS], blockTorque[SHARED_LOAD_SLOTS];
    __shared__ unsigned int blockReal, blockSS;
    const unsigned int slots = numNonClump < SHARED_LOAD_SLOTS ? numNonClump : SHARED_LOAD_SLOTS;
    for (unsigned int k = threadIdx.x; k < slots; k += blockDim.x) {
        blockForce[k] = make_float3(0.f);
        blockTorque[k] = make_float3(0.f);
    }
    if (threadIdx.x == 0) blockReal = blockSS = 0;
    __syncthreads();

    if (i < s.numContacts) {
        const ContactView& c = s.contacts;
        bool applied;
        ContactLoad load;
        bool touching;
        if constexpr (Pooled) {
            touching = pooledContactStep<Model, kType>(s, model, i, ids, time, dt, applied, load);
        } else {
            touching = contactStepOfType<Model, kType>(s, model, i, ids, time, dt, applied, load);
            if (c.force) c.force[i] = applied ? load.force : make_float3(0.f);
        }
        // A load of zeros adds nothing (an owner's sum starts at +0 and so never is -0, which a +0
        // or -0 added would change): a custom model, called for every pair, exerts zeros on most.
        if (applied && !isZeroLoad(load)) {
            atomicAddLoad(s.owners.contactForce, load.ownerA, s.numOwners, load.force);
            atomicAddLoad(s.owners.contactTorque, load.ownerA, s.numOwners, load.torqueA);
            const unsigned int slot = load.ownerB - firstNonClump;
            if (load.ownerB >= firstNonClump && slot < slots) {
                atomicAdd3(&blockForce[slot], -load.force);
                atomicAdd3(&blockTorque[slot], load.torqueB);
            } else {
                atomicAddLoad(s.owners.contactForce, load.ownerB, s.numOwners, -load.force);
                atomicAddLoad(s.owners.contactTorque, load.ownerB, s.numOwners, load.torqueB);
            }
        }
        if (touching) {
            atomicAdd(&blockReal, 1u);
            if (ids.type == SPHERE_SPHERE) atomicAdd(&blockSS, 1u);
        }
    }
    __syncthreads();
    for (unsigned int k = threadIdx.x; k < slots; k += blockDim.x) {
        const float3 f = blockForce[k], t = blockTorque[k];
        if (!isZero(f)) atomicAddLoad(s.owners.contactForce, firstNonClump + k, s.numOwners, f);
        if (!isZero(t)) atomicAddLoad(s.owners.contactTorque, firstNonClump + k, s.numOwners, t);
    }
    if (threadIdx.x == 0) {
        if (blockReal) atomicAdd(&red->realContacts, (unsigned long long)blockReal);
        if (blockSS) atomicAdd(&red->realSphereSphere, (unsigned long long)blockSS);
    }
}

}  // namespace deme
