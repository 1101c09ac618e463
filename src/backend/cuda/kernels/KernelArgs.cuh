// Arguments shared by the host side of the CUDA backend and its kernels (compiled at run time by
// NVRTC). Plain data only.
#pragma once

#include <deme/VariableTypes.h>

#include "dynamics/StepBatch.h"

namespace deme {

// Per-step results that kernels combine with atomics; the step's last kernel (deme_place_and_finish)
// tallies them into the batch's control block (dynamics/StepBatch.h) and clears them for the next.
struct StepReduction {
    unsigned long long maxTravelBits;  // largest travel since detection (a non-negative double's bits)
    unsigned int maxSpeedBits;         // fastest geometry point (a non-negative float's bits)
    unsigned int firstFault;           // lowest owner id with a fault, or 0xFFFFFFFF
    unsigned int anyLargeRotation;
    unsigned int errorFlags;  // KernelError bits
    unsigned int errorItem;   // the item (owner, sphere) that raised the first error flag
    unsigned int parkedOwners;  // clumps parked in the step (dynamics/OwnerStep.h)
    unsigned long long realContacts, realSphereSphere;
};

// Errors kernels can raise; the host turns them into deme::Error.
enum KernelError : unsigned int {
    KERNEL_ERROR_MESH_CANDIDATES = 1,  // a sphere touches more triangles than a kernel can sort
};

// Non-clump owners (walls, meshes) whose contact loads a block sums in shared memory before adding
// them to device memory: all contacts of a floor land on one owner, and per-contact atomics on one
// address would serialise.
constexpr unsigned int SHARED_LOAD_SLOTS = 64;

// deme_integrate_and_place's `analyticalBlock` where no one block steps every analytical owner (the
// block that finishes last places their components then).
constexpr unsigned int NO_ANALYTICAL_BLOCK = 0xFFFFFFFFu;

}  // namespace deme
