// Arguments shared by the host side of the CUDA backend and its kernels (compiled at run time by
// NVRTC). Plain data only.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

// Per-step results that kernels combine with atomics and the host reads back after each step.
struct StepReduction {
    unsigned long long maxTravelBits;  // largest travel since detection (a non-negative double's bits)
    unsigned int maxSpeedBits;         // fastest geometry point (a non-negative float's bits)
    unsigned int firstFault;           // lowest owner id with a fault, or 0xFFFFFFFF
    unsigned int anyLargeRotation;
    unsigned int errorFlags;  // KernelError bits
    unsigned int errorItem;   // the item (owner, sphere) that raised the first error flag
    unsigned int pad;
    unsigned long long realContacts, realSphereSphere;
};

// Errors kernels can raise; the host turns them into deme::Error.
enum KernelError : unsigned int {
    KERNEL_ERROR_MESH_CANDIDATES = 1,  // a sphere touches more triangles than a kernel can sort
};

// Most overlapping sphere-triangle contacts one sphere may have (the smooth-surface rule sorts them
// in a local array).
constexpr unsigned int MAX_MESH_CANDIDATES = 64;
// Non-clump owners (walls, meshes) whose contact loads a block sums in shared memory before adding
// them to device memory: all contacts of a floor land on one owner, and per-contact atomics on one
// address would serialise.
constexpr unsigned int SHARED_LOAD_SLOTS = 64;

// The bin grid of contact detection, for kernels.
struct BinGridView {
    double3 origin;
    double size;
    int nx, ny, nz;
};

// What the pair search reads besides the state.
struct PairSearchArgs {
    BinGridView grid;
    double margin;
    const float* familyExtraMargin;
    const uint8_t* familyMask;  // NUM_FAMILIES x NUM_FAMILIES
    const int *sphereBinLo, *sphereBinHi;
    const unsigned int *sphereBinStart, *sphereBinItems;
    const unsigned int *triBinStart, *triBinItems;
    const double3 *triLo, *triHi;
};

}  // namespace deme
