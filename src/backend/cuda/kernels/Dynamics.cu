// The dynamics side on the GPU: mesh contact rule, the built-in models' force passes, integration
// and pose caches. Compiled at run time by NVRTC together with the physics headers; every per-item
// function here is the one the CPU sweeps call.
#include "backend/cuda/kernels/DependentLaunch.cuh"
#include "backend/cuda/kernels/ForceModelParams.cuh"
#include "backend/cuda/kernels/ForcePassKernel.cuh"
#include "backend/cuda/kernels/KernelArgs.cuh"
#include "dynamics/ContactInputsGather.h"
#include "dynamics/MeshContactRule.h"
#include "dynamics/OwnerStep.h"
#include "physics/BuiltInForceModels.h"
#include "state/StateView.h"

namespace deme {

namespace {

__device__ inline size_t globalIndex() { return (size_t)blockIdx.x * blockDim.x + threadIdx.x; }

__device__ inline void raiseError(StepReduction* red, unsigned int flag, unsigned int item) {
    if (atomicOr(&red->errorFlags, flag) == 0u) red->errorItem = item;
}

// The GPU's nanosecond clock, the same on every multiprocessor.
__device__ inline unsigned long long deviceClockNs() {
    unsigned long long t;
    asm volatile("mov.u64 %0, %%globaltimer;" : "=l"(t));
    return t;
}

}  // namespace

// The steps of a batch (dynamics/StepBatch.h): every step kernel takes the batch's control block and
// does nothing once it says the batch has ended, so that the host can queue a whole batch of steps
// (replays of one captured step, backend/cuda/StepGraph.h) and look only at its end.
__device__ inline void clearReduction(StepReduction* red) {
    red->maxTravelBits = 0ull;
    red->maxSpeedBits = 0u;
    red->firstFault = NO_FAULT;
    red->anyLargeRotation = 0u;
    red->errorFlags = 0u;
    red->errorItem = 0u;
    red->realContacts = red->realSphereSphere = 0ull;
    red->parkedOwners = 0u;
}

// Before a batch: its control block, and a clear reduction for its first step. One thread.
extern "C" __global__ void deme_begin_batch(StepBatchControl* ctl, double time, double dt, double margin,
                                            StepReduction* red) {
    if (globalIndex() != 0) return;
    *ctl = beginStepBatch(time, dt, margin);
    ctl->forcePhaseStartNs = deviceClockNs();  // the first step's force phase starts after this
    clearReduction(red);
}

// A step's first kernel where integration does not clear the loads it read (integrateOwner): clears
// the loads of owners ids[0, n) (the active box's owners that a step may load; every owner if ids is
// null) before the force pass, whose phase starts here then.
extern "C" __global__ void deme_clear_loads(StepBatchControl* ctl, float3* contactForce, float3* contactTorque,
                                            const bodyID_t* ids, unsigned int n) {
    beginDependentKernel();
    if (ctl->stop) return;
    const size_t k = globalIndex();
    if (k == 0) ctl->forcePhaseStartNs = deviceClockNs();
    if (k >= n) return;
    const size_t o = ids ? (size_t)ids[k] : k;
    contactForce[o] = make_float3(0.f);
    contactTorque[o] = make_float3(0.f);
}

// The analytical owners' step, by one block: its threads place the components, one each, with
// their surface speeds (placeAnalytical), then step each owner's travel by its fastest component
// (the CPU's sweep does the same serially, backend/cpu/Integration.cpp). In parallel over the
// components, because every component's loads wait for its owner's pose: one after the other, a
// handful of walls cost as much as the rest of the step.
__device__ inline void stepAnalyticalOwners(StateView& s, float* componentSpeed, unsigned int firstAnalyticalOwner,
                                            unsigned int numAnalyticalOwners, float h, double domainDiagonal,
                                            StepReduction* red) {
    for (unsigned int k = threadIdx.x; k < s.numAnalytical; k += blockDim.x)
        componentSpeed[k] = placeAnalytical(s, k, domainDiagonal);
    __syncthreads();  // the block's global writes are visible to the block after it
    for (unsigned int j = threadIdx.x; j < numAnalyticalOwners; j += blockDim.x) {
        const unsigned int o = firstAnalyticalOwner + j;
        float rate = 0.f;
        for (unsigned int k = 0; k < s.numAnalytical; k++)
            if (s.analytical.owner[k] == o) rate = fmaxf(rate, componentSpeed[k]);
        const float travel = s.owners.travel[o] + rate * h;
        s.owners.travel[o] = travel;
        if (travel > 0.f) atomicMax(&red->maxTravelBits, (unsigned long long)__double_as_longlong((double)travel));
        if (rate > 0.f) atomicMax(&red->maxSpeedBits, __float_as_uint(rate));
    }
}

// The end of a step, run by one thread once everything else of the step is done: the step's tally
// into the control block (the rule that may end the batch) and a clear reduction for the next.
__device__ inline void finishStep(StepBatchControl* ctl, StepReduction* red) {
    StepTally t;
    t.maxTravel = __longlong_as_double((long long)red->maxTravelBits);
    t.maxSpeed = __uint_as_float(red->maxSpeedBits);
    t.firstFault = red->firstFault;
    t.errorFlags = red->errorFlags;
    t.errorItem = red->errorItem;
    t.realContacts = red->realContacts;
    t.realSphereSphere = red->realSphereSphere;
    t.parkedOwners = red->parkedOwners;
    finishBatchStep(*ctl, t);
    clearReduction(red);
    ctl->forcePhaseNs += ctl->forcePhaseEndNs - ctl->forcePhaseStartNs;  // stamped by integration's block 0
    ctl->forcePhaseStartNs = deviceClockNs();  // the next step's force phase starts once this kernel ends
}

// One thread per sphere-triangle contact that opens its sphere's run (contacts are sorted by
// sphere, a sphere's triangle contacts last).
extern "C" __global__ void deme_resolve_mesh_contacts(StateView s, const StepBatchControl* ctl, StepReduction* red) {
    beginDependentKernel();
    if (ctl->stop) return;
    const size_t i = globalIndex();
    const ContactView& c = s.contacts;
    const bodyID_t firstTriangle = s.triangleIdBase();  // B from here on: a sphere-triangle pair
    if (i >= s.numContacts || c.geomB[i] < firstTriangle) return;
    const bodyID_t a = pairAOf(s, i);
    if (i > 0 && c.geomB[i - 1] >= firstTriangle && pairAOf(s, i - 1) == a) return;
    size_t n = 1;
    while (i + n < s.numContacts && c.geomB[i + n] >= firstTriangle && pairAOf(s, i + n) == a) n++;
    MeshCandidate cand[MAX_MESH_CANDIDATES];
    // In the pooled form every sphere-triangle pair has a slot (DeviceHistoryMapping).
    const HistoryPoolView& hp = s.historyPool;
    const bool resolved = hp.ranked ? resolveSphereMeshContactsWith(s, a, i, n, cand, MAX_MESH_CANDIDATES,
                                                                    HistoryInPool{hp, c.meshState, s.numWildcards})
                                    : resolveSphereMeshContacts(s, i, n, cand, MAX_MESH_CANDIDATES);
    if (!resolved) raiseError(red, KERNEL_ERROR_MESH_CANDIDATES, a);
}

// The built-in models from the material tables.
__device__ inline FrictionalHertzModel frictionalHertzModel(const ForceModelParams& p) {
    const unsigned int n = p.numMaterials;
    return FrictionalHertzModel{PairTable{p.mu, n}, PairTable{p.Crr, n}, PairTable{p.E_eff, n}, PairTable{p.G_eff, n},
                                PairTable{p.beta_CoR, n}};
}
__device__ inline FrictionlessHertzModel frictionlessHertzModel(const ForceModelParams& p) {
    return FrictionlessHertzModel{PairTable{p.E_eff, p.numMaterials}, PairTable{p.beta_CoR, p.numMaterials}};
}

// Force passes of the built-in models (kernels/ForcePassKernel.cuh); a custom model's pass is
// generated and compiled at Initialize (forcemodel/CudaCodeGen.cpp). All take the same arguments.
// The _r64 variants, the ones used (DeviceForceModel.cpp), cap the registers at 64: four blocks of 256
// threads fit a multiprocessor instead of two, for 48 bytes spilled (to L1). Measured on one H200:
// +5 % steps per second on both SMALL-SYSTEMS cases (BENCHMARKS.md).
#define DEME_BUILT_IN_FORCE_PASSES(SUFFIX, ATTR, NO_TRIANGLES)                                                  \
    extern "C" __global__ void ATTR deme_force_pass_frictional_hertz##SUFFIX(                                   \
        StateView s, const StepBatchControl* ctl, ForceModelParams p, unsigned int firstNonClump,               \
        unsigned int numNonClump, StepReduction* red) {                                                         \
        forcePassKernel<FrictionalHertzModel, NO_TRIANGLES>(s, frictionalHertzModel(p), ctl, firstNonClump,     \
                                                            numNonClump, red);                                  \
    }                                                                                                           \
    extern "C" __global__ void ATTR deme_force_pass_frictionless_hertz##SUFFIX(                                 \
        StateView s, const StepBatchControl* ctl, ForceModelParams p, unsigned int firstNonClump,               \
        unsigned int numNonClump, StepReduction* red) {                                                         \
        forcePassKernel<FrictionlessHertzModel, NO_TRIANGLES>(s, frictionlessHertzModel(p), ctl, firstNonClump, \
                                                              numNonClump, red);                                \
    }
// The frictional model's passes over a set whose history is pooled (dynamics/PooledContactStep.h).
#define DEME_POOLED_FORCE_PASS(SUFFIX, ATTR, NO_TRIANGLES)                                                        \
    extern "C" __global__ void ATTR deme_force_pass_frictional_hertz##SUFFIX(                                     \
        StateView s, const StepBatchControl* ctl, ForceModelParams p, unsigned int firstNonClump,                 \
        unsigned int numNonClump, StepReduction* red) {                                                           \
        forcePassKernel<FrictionalHertzModel, NO_TRIANGLES, true>(s, frictionalHertzModel(p), ctl, firstNonClump, \
                                                                  numNonClump, red);                              \
    }
DEME_BUILT_IN_FORCE_PASSES(, , false)
DEME_BUILT_IN_FORCE_PASSES(_r64, __maxnreg__(64), false)
// Scenes without meshes (DeviceForceModel::record).
DEME_BUILT_IN_FORCE_PASSES(_no_mesh, , true)
DEME_BUILT_IN_FORCE_PASSES(_no_mesh_r64, __maxnreg__(64), true)
DEME_POOLED_FORCE_PASS(_pooled, , false)
DEME_POOLED_FORCE_PASS(_pooled_r64, __maxnreg__(64), false)
DEME_POOLED_FORCE_PASS(_pooled_no_mesh, , true)
DEME_POOLED_FORCE_PASS(_pooled_no_mesh_r64, __maxnreg__(64), true)

// What thread k of an owner step reads before its owner's contact loads: the owner ids[k] (k if ids
// is null; the active box leaves fixed owners at rest out, deme_stepped_flags) and its step's inputs
// (dynamics/OwnerStep.h), with the step's prescriptions from the batch's table's row for it
// (motion[stepsDone * NUM_FAMILIES + family], codegen/FamilyMotionSource.h). owner is -1 for a
// thread past the end.
struct OwnerStepStart {
    long long owner;
    OwnerStepInputs in;
};

__device__ inline OwnerStepStart loadOwnerStepStart(const StateView& s, const StepBatchControl* ctl,
                                                    const FamilyStepMotion* motion, const StepConstants& consts,
                                                    const bodyID_t* ids, unsigned int n) {
    OwnerStepStart st;
    st.owner = -1;
    const size_t k = globalIndex();
    if (k >= n) return st;
    const size_t o = ids ? (size_t)ids[k] : k;
    const FamilyStepMotion* stepMotion = motion + (size_t)ctl->stepsDone * NUM_FAMILIES;
    st.owner = (long long)o;
    st.in = loadOwnerStepInputs(s, o, stepMotion[s.owners.family[o]], consts);
    return st;
}

// The start of the owner-step kernels below: the dependent launch's wait (DependentLaunch.cuh) and
// the owner's inputs. Where the kernel before is the force pass (inputsBeforeWait), which writes
// none of the inputs -- they were last written by the step before, which had ended before that
// pass could start -- they are read before the wait: their round trips overlap the pass's last
// blocks instead of lengthening the step. So is the batch's stop flag (the pass only reads it), so
// that the loads' wait after the wait is one round trip, not two in a row. Anything else before (no
// force pass where there are no contacts: then the kernel before may be the last step's
// integration) and they are read after it. Returns false where the batch has stopped.
__device__ inline bool startOwnerStep(const StateView& s, StepBatchControl* ctl, const FamilyStepMotion* motion,
                                      const StepConstants& consts, const bodyID_t* ids, unsigned int n,
                                      unsigned int inputsBeforeWait, OwnerStepStart& st) {
    unsigned int stop = 0u;
    if (inputsBeforeWait) {
        st = loadOwnerStepStart(s, ctl, motion, consts, ids, n);
        stop = ctl->stop;
    }
    beginDependentKernel();
    // A pass that left pairs pending (the pooled history, dynamics/PooledContactStep.h) stops the
    // batch before integration: the host grows the pool and runs the step's rest (CudaStepBatch.cpp).
    if (historyPoolPaused(s.historyPool)) {
        if (blockIdx.x == 0 && threadIdx.x == 0) ctl->stop = 1u;
        return false;
    }
    if (inputsBeforeWait) return stop == 0u;
    if (ctl->stop) return false;
    st = loadOwnerStepStart(s, ctl, motion, consts, ids, n);
    return true;
}

#ifndef DEME_STEP_BLOCK_REDUCTION
#define DEME_STEP_BLOCK_REDUCTION 1
#endif

// The step's maxima and first fault over the block's owners, into the step's reduction: combined
// per warp (shuffles), then per block (shared memory, after a barrier: every thread of the block
// calls this), and added by thread 0. The atomics on the reduction's few addresses are served one
// after the other, and the block's count (lastBlockToFinish) waits for its own: one set a block
// instead of one a warp is a quarter of them in blocks of 128.
__device__ inline void addStepMaxima(double travel, float speed, unsigned int fault, unsigned int large,
                                     StepReduction* red) {
    for (int off = 16; off > 0; off >>= 1) {
        travel = fmax(travel, __shfl_down_sync(0xFFFFFFFFu, travel, off));
        speed = fmaxf(speed, __shfl_down_sync(0xFFFFFFFFu, speed, off));
        fault = min(fault, __shfl_down_sync(0xFFFFFFFFu, fault, off));
        large |= __shfl_down_sync(0xFFFFFFFFu, large, off);
    }
    const unsigned int lane = threadIdx.x & 31u, warp = threadIdx.x >> 5;
    if (DEME_STEP_BLOCK_REDUCTION) {
        __shared__ double warpTravel[32];
        __shared__ float warpSpeed[32];
        __shared__ unsigned int warpFault[32], warpLarge[32];
        if (lane == 0u) {
            warpTravel[warp] = travel;
            warpSpeed[warp] = speed;
            warpFault[warp] = fault;
            warpLarge[warp] = large;
        }
        __syncthreads();
        if (threadIdx.x != 0u) return;
        for (unsigned int w = 1; w < (blockDim.x + 31u) / 32u; w++) {
            travel = fmax(travel, warpTravel[w]);
            speed = fmaxf(speed, warpSpeed[w]);
            fault = min(fault, warpFault[w]);
            large |= warpLarge[w];
        }
    } else if (lane != 0u) {
        return;
    }
    if (travel > 0.0) atomicMax(&red->maxTravelBits, (unsigned long long)__double_as_longlong(travel));
    if (speed > 0.f) atomicMax(&red->maxSpeedBits, __float_as_uint(speed));
    if (fault != NO_FAULT) atomicMin(&red->firstFault, fault);
    if (large) red->anyLargeRotation = 1u;
}

// Owner st.owner's step, the first part of the two integration kernels below, with the step's
// maxima and first fault added to the step's reduction (addStepMaxima; every thread of the block
// calls this). An owner whose rotation this step was too large for
// the series step takes the exact (scalar) step at once (rare; the CPU does these in a sweep of
// their own so that its main sweep vectorises). With clearLoads the
// owner's contact loads are cleared once read, ready for the next step's force pass (not in a step
// whose loads the host reads after it, the storing step, nor where deme_clear_loads clears them at
// every step's start). Returns the owner stepped, or -1 for a thread past the end.
__device__ inline long long integrateOwner(StateView& s, StepBatchControl* ctl, const OwnerStepStart& st,
                                           const StepConstants& consts, unsigned int clearLoads,
                                           StepReduction* red) {
    const size_t k = globalIndex();
    // The force phase has ended (the kernels of a stream run one after the other); the step's end
    // adds it up (finishStep). A store, not an update here: reading the start back would put a round
    // trip before this thread's owner, and block 0 would often be the step's last.
    if (k == 0) ctl->forcePhaseEndNs = deviceClockNs();
    double travel = 0.0;
    float speed = 0.f;
    unsigned int fault = NO_FAULT, large = 0u;
    bool parked = false;
    if (st.owner >= 0) {
        const size_t o = (size_t)st.owner;
        const float3 force = s.owners.contactForce[o], torque = s.owners.contactTorque[o];
        const OwnerStepResult r = stepOwner(s, o, st.in, force, torque, consts);
        s.integrationScratch.flags[o] = r.flags;
        travel = r.travelSinceDetection > 0.f ? (double)r.travelSinceDetection : 0.0;
        speed = r.speed;
        if (r.flags & STEP_FAULTS) fault = (unsigned int)o;
        parked = (r.flags & STEP_PARKED) != 0;
        large = (r.flags & STEP_LARGE_ROTATION) ? 1u : 0u;
        if (large) finishLargeRotation(s, o, st.in, torque, consts.h);
        if (clearLoads) {
            s.owners.contactForce[o] = make_float3(0.f);
            s.owners.contactTorque[o] = make_float3(0.f);
        }
    }
    // Parked clumps are counted by warp (every thread of the block gets here): one atomic a warp.
    const unsigned int parkedInWarp = __popc(__ballot_sync(0xFFFFFFFFu, parked));
    if (parkedInWarp && (threadIdx.x & 31u) == 0u) atomicAdd(&red->parkedOwners, parkedInWarp);
    addStepMaxima(travel, speed, fault, large, red);
    return st.owner;
}

// A device-scope acquire-release fence: enough to order a block's writes before its count and a
// count before the reads of the block that saw it last (a release and an acquire pattern of the
// PTX memory model), and lighter than __threadfence's sequentially consistent one.
__device__ inline void fenceAcqRelDevice() { asm volatile("fence.acq_rel.gpu;" ::: "memory"); }

// Counts this block as done (thread 0, after the barrier that ends the block's writes); true in the
// block that is the grid's last (`blocksDone` counts them, and is zero again once the last has).
// Each block's global writes before the barrier are visible to the last one after this.
__device__ inline bool countBlockDone(unsigned int* blocksDone) {
    fenceAcqRelDevice();
    if (atomicAdd(blocksDone, 1u) != gridDim.x - 1) return false;
    *blocksDone = 0u;
    fenceAcqRelDevice();  // between seeing the count and reading what the other blocks wrote
    return true;
}

// Whether this block is the grid's last to get here, for every thread of the block.
__device__ inline bool lastBlockToFinish(unsigned int* blocksDone) {
    __shared__ bool lastBlock;
    __syncthreads();
    if (threadIdx.x == 0) lastBlock = countBlockDone(blocksDone);
    __syncthreads();
    return lastBlock;
}

// The same where only thread 0 of the last block goes on: the other threads of every block return
// once the block's writes are done, without waiting on the count's round trips, and their
// multiprocessor's room is the next kernel's sooner.
__device__ inline bool lastBlockToFinishThread0(unsigned int* blocksDone) {
    __syncthreads();
    return threadIdx.x == 0 && countBlockDone(blocksDone);
}

// Integration of the stepped owners, one thread each (integrateOwner); the spheres are placed by
// deme_place_and_finish after it.
extern "C" __global__ void deme_integrate(StateView s, StepBatchControl* ctl, const FamilyStepMotion* motion,
                                          StepConstants consts, const bodyID_t* ids, unsigned int n,
                                          unsigned int inputsBeforeWait, unsigned int clearLoads, StepReduction* red) {
    OwnerStepStart st;
    if (!startOwnerStep(s, ctl, motion, consts, ids, n, inputsBeforeWait, st)) return;
    integrateOwner(s, ctl, st, consts, clearLoads, red);
}

// A step's last kernel after deme_integrate: the cached poses after integration -- spheres ids[0,
// numSpheres) of the owners stepped (every sphere if ids is null), then every triangle of an owner
// that moved, one thread per item; block 0 also steps the analytical owners (stepAnalyticalOwners,
// `componentSpeed` one float per analytical component) -- and the end of the step (finishStep), by
// the block that finishes last. The end needs nothing of the poses, so one kernel does both; the
// block that sets ctl->stop is the last one to read it.
extern "C" __global__ void deme_place_and_finish(StateView s, StepBatchControl* ctl, const bodyID_t* ids,
                                                 unsigned int numSpheres, unsigned int numTriangles,
                                                 unsigned int firstAnalyticalOwner, unsigned int numAnalyticalOwners,
                                                 float h, double domainDiagonal, StepReduction* red,
                                                 float* componentSpeed, unsigned int* blocksDone) {
    beginDependentKernel();
    if (ctl->stop) return;
    const size_t k = globalIndex();
    if (k < numSpheres) {
        placeSphere(s, ids ? (size_t)ids[k] : k);
    } else {
        const size_t t = k - numSpheres;
        if (t < numTriangles && (s.integrationScratch.flags[s.triangles.owner[t]] & STEP_MOVED)) placeTriangle(s, t);
    }
    if (blockIdx.x == 0)
        stepAnalyticalOwners(s, componentSpeed, firstAnalyticalOwner, numAnalyticalOwners, h, domainDiagonal, red);
    if (lastBlockToFinishThread0(blocksDone)) finishStep(ctl, red);
}

// Integration and placement in one kernel, for scenes without triangles (whose placement waits for
// every owner): the thread that steps an owner places its spheres (ownerSphereStart: owner o's are
// [start[o], start[o + 1]); null where spheres are their owners, state/SphereLayout.h). The
// analytical owners' components are placed once their owners' poses are: by the block that stepped
// all of them (`analyticalBlock`, where one did: every owner stepped and the analytical ones within
// one block's range), right after its owners, or else by the block that finishes last, which ends
// the step. One kernel boundary fewer than deme_integrate and deme_place_and_finish, the spheres
// read their owner's new pose where it was just written, and the step's serial tail is the tally.
extern "C" __global__ void deme_integrate_and_place(StateView s, StepBatchControl* ctl, const FamilyStepMotion* motion,
                                                    StepConstants consts, const bodyID_t* ids, unsigned int n,
                                                    unsigned int inputsBeforeWait, unsigned int clearLoads,
                                                    const uint32_t* ownerSphereStart, unsigned int firstAnalyticalOwner,
                                                    unsigned int numAnalyticalOwners, unsigned int analyticalBlock,
                                                    double domainDiagonal, StepReduction* red, float* componentSpeed,
                                                    unsigned int* blocksDone) {
    OwnerStepStart st;
    if (!startOwnerStep(s, ctl, motion, consts, ids, n, inputsBeforeWait, st)) return;
    const long long o = integrateOwner(s, ctl, st, consts, clearLoads, red);
    if (o >= 0 && ownerSphereStart)
        for (uint32_t i = ownerSphereStart[o], end = ownerSphereStart[o + 1]; i < end; i++) placeSphere(s, i);
    if (blockIdx.x == analyticalBlock) {
        __syncthreads();  // the block's owners' poses are in place (a barrier orders the block's global writes)
        stepAnalyticalOwners(s, componentSpeed, firstAnalyticalOwner, numAnalyticalOwners, consts.h, domainDiagonal,
                             red);
    }
    if (analyticalBlock != NO_ANALYTICAL_BLOCK || numAnalyticalOwners == 0) {
        if (lastBlockToFinishThread0(blocksDone)) finishStep(ctl, red);
        return;
    }
    if (!lastBlockToFinish(blocksDone)) return;
    stepAnalyticalOwners(s, componentSpeed, firstAnalyticalOwner, numAnalyticalOwners, consts.h, domainDiagonal, red);
    __syncthreads();  // the analytical owners' travel in the reduction before the tally
    if (threadIdx.x == 0) finishStep(ctl, red);
}

// *anyAtRest = 1 if some owner is fixed and at rest (its step would be itself: the active box's
// dormant grains); left as it was otherwise. One thread per owner. Where none is, every owner is
// stepped and the step needs no lists (deme_stepped_flags).
extern "C" __global__ void deme_any_owner_at_rest(StateView s, const FamilyStepMotion* motion,
                                                  unsigned int* anyAtRest) {
    const size_t o = globalIndex();
    if (o < s.numOwners && ownerAtRest(s, motion, o)) *anyAtRest = 1u;
}

// Which owners and spheres a step integrates and places (backend/cpu/Integration.h,
// IntegrationSubset): 1 in ownerStepped[o] unless owner o is fixed and at rest, 1 in
// sphereStepped[i] if its owner is stepped. One thread per owner and per sphere.
extern "C" __global__ void deme_stepped_flags(StateView s, const FamilyStepMotion* motion, unsigned int* ownerStepped,
                                              unsigned int* sphereStepped) {
    const size_t i = globalIndex();
    if (i < s.numOwners) ownerStepped[i] = ownerAtRest(s, motion, i) ? 0u : 1u;
    if (i < s.numSpheres) sphereStepped[i] = ownerAtRest(s, motion, sphereOwner(s, i)) ? 0u : 1u;
}

// The active box: flags[o] = 1 for the owners of both geometries of every contact of the set (the
// owners whose loads a step may change besides the stepped ones). One thread per contact.
extern "C" __global__ void deme_mark_contact_owners(StateView s, unsigned int* flags) {
    const size_t i = globalIndex();
    if (i >= s.numContacts) return;
    const ContactView& c = s.contacts;
    flags[sphereOwner(s, pairAOf(s, i))] = 1u;
    flags[geometryOwner(s, contactTypeAt(s, i), c.geomB[i])] = 1u;
}

// ids[offset[i]] = i for every i < n with flags[i] set (offset: the flags' exclusive sum).
extern "C" __global__ void deme_scatter_flagged(const unsigned int* flags, const unsigned int* offset, unsigned int n,
                                                bodyID_t* ids) {
    const size_t i = globalIndex();
    if (i < n && flags[i]) ids[offset[i]] = (bodyID_t)i;
}

// flags[ids[k]] = 1 for k < n.
extern "C" __global__ void deme_flag_listed(const bodyID_t* ids, unsigned int n, unsigned int* flags) {
    const size_t k = globalIndex();
    if (k < n) flags[ids[k]] = 1u;
}

// A tracker's rows of the last step's loads: out[k] = force[ids[k]], out[n + k] = torque[ids[k]].
extern "C" __global__ void deme_gather_owner_loads(const float3* force, const float3* torque, const bodyID_t* ids,
                                                   unsigned int n, float3* out) {
    const size_t k = globalIndex();
    if (k >= n) return;
    out[k] = force[ids[k]];
    out[n + k] = torque[ids[k]];
}

// The stepped owners and spheres at their offsets (the flags' exclusive sums), ascending.
extern "C" __global__ void deme_stepped_scatter(StateView s, const unsigned int* ownerStepped,
                                                const unsigned int* ownerOffset, const unsigned int* sphereStepped,
                                                const unsigned int* sphereOffset, bodyID_t* owners, bodyID_t* spheres) {
    const size_t i = globalIndex();
    if (i < s.numOwners && ownerStepped[i]) owners[ownerOffset[i]] = (bodyID_t)i;
    if (i < s.numSpheres && sphereStepped[i]) spheres[sphereOffset[i]] = (bodyID_t)i;
}

}  // namespace deme
