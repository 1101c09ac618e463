// A batch of steps that the dynamics side runs without the host looking in between, and the one
// rule, run after every step of it, that decides whether the batch goes on. Both backends take the
// same rule: the CPU after each step of its loop, the GPU in a one-thread kernel at the end of each
// step (kernels/Dynamics.cu), so that a GPU queues a whole batch of steps with one host
// synchronisation at its end instead of one per step (docs/cuda-backend.md, "Step batches").
//
// A batch ends early after a step that lets the contact set in use expire (some owner travelled
// beyond its margin since the set's snapshot), found a fault (an owner diverged or left the domain)
// or raised a kernel error: the steps queued after it do nothing (every step kernel returns at once
// once `stop` is set), and the host takes over exactly where the per-step loop would have.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

// What one step found, as the end-of-step rule sees it.
struct StepTally {
    double maxTravel;  // largest travel of any owner since the set in use was detected
    float maxSpeed;    // fastest geometry point
    unsigned int firstFault;  // lowest owner with a fault, NO_FAULT if none
    unsigned int errorFlags;  // KernelError bits (GPU)
    unsigned int errorItem;
    unsigned long long realContacts, realSphereSphere;
    unsigned int parkedOwners;  // clumps parked after the step (OwnerStep.h, parkingPosition)
};

constexpr unsigned int NO_FAULT = 0xFFFFFFFFu;

// Steps a batch may hold at most: a GPU queues them with one host synchronisation at the end, so a
// long batch costs it nothing; the cap keeps the progress report and STEP_METRIC lines regular, and
// sizes the GPU's table of a batch's prescriptions (codegen/FamilyMotionSource.h).
constexpr unsigned long long MAX_BATCH_STEPS = 256;

// The batch's control block: set by the host before the batch, advanced after each step, read back
// once after it (on the GPU it lives in device memory).
struct StepBatchControl {
    double time;    // simulation time at the start of the next step
    double dt;
    double margin;  // the set in use's margin: a travel beyond it ends the batch
    unsigned int stop;       // nonzero: the batch has ended; its remaining steps do nothing
    unsigned int stepsDone;  // steps completed in this batch
    unsigned long long realContactSum;  // pairs in contact, summed over the batch's steps
    StepTally last;                     // the last completed step's tally
    // GPU only (the CPU times its phases on the host): the device clock at the start and at the end
    // of the step's force phase, and the force phases' device time summed over the batch, in
    // nanoseconds; read inside replayed step graphs, where events cannot time a part of the step.
    unsigned long long forcePhaseStartNs, forcePhaseEndNs, forcePhaseNs;
};

DEME_HD_INLINE StepBatchControl beginStepBatch(double time, double dt, double margin) {
    StepBatchControl c;
    c.time = time;
    c.dt = dt;
    c.margin = margin;
    c.stop = 0u;
    c.stepsDone = 0u;
    c.realContactSum = 0ull;
    c.forcePhaseStartNs = c.forcePhaseEndNs = c.forcePhaseNs = 0ull;
    c.last.maxTravel = 0.0;
    c.last.maxSpeed = 0.f;
    c.last.firstFault = NO_FAULT;
    c.last.errorFlags = 0u;
    c.last.errorItem = 0u;
    c.last.realContacts = c.last.realSphereSphere = 0ull;
    c.last.parkedOwners = 0u;
    return c;
}

// Whether the step just tallied ends the batch: the host must look (the set in use expired, or an
// owner faulted, or a kernel raised an error).
DEME_HD_INLINE bool stepEndsBatch(const StepBatchControl& c, const StepTally& t) {
    return t.maxTravel > c.margin || t.firstFault != NO_FAULT || t.errorFlags != 0u;
}

// After each step of a batch: the clock (the same double additions as a per-step loop), the
// counters, and whether the batch goes on.
DEME_HD_INLINE void finishBatchStep(StepBatchControl& c, const StepTally& t) {
    c.time += c.dt;
    c.stepsDone++;
    c.realContactSum += t.realContacts;
    c.last = t;
    if (stepEndsBatch(c, t)) c.stop = 1u;
}

}  // namespace deme
