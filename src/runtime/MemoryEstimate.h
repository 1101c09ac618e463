// What a run will hold in the memory its steps use (the GPU's on the CUDA backend, the host's on the
// CPU's) once its first contact set is built, estimated at Initialize from the scene's counts and the
// state's field lists (state/StateFields.h), group by group as ShowMemoryStats counts them. A scene
// that does not fit then fails at Initialize with a deme::Error saying what it needs and what there
// is, not in its first detection (docs/memory.md, "Scenes too large").
#pragma once

#include <deme/MemoryStats.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "kinematics/BinGrid.h"
#include "state/SimState.h"

namespace deme {

// The first contact set's size the estimate assumes: six pairs per sphere, what a dense packing
// within the margin has (MIXER-BENCH early spheres, a lattice closer than the margin: 5.95; a
// settled bed of spheres: 4-7). A set that grows beyond what the memory holds later is an error
// naming the set and its size (requireRoomForContactSet).
constexpr double ESTIMATED_PAIRS_PER_SPHERE = 6.0;
// The CPU's force reduction: window slots per owner (one per distinct B owner of a block's contacts
// outside the block, backend/cpu/ForcePassLoop.h); MIXER-BENCH early spheres hold 0.52, the
// compressed block of clumps of the tests 0.75.
constexpr double ESTIMATED_WINDOW_SLOTS_PER_OWNER = 0.75;
// The share of a set's pairs whose B owner is outside A's block, each with a window slot (the early
// mixer's spheres and CPU-BED's bed: 0.23).
constexpr double ESTIMATED_CROSSING_PAIR_SHARE = 0.3;

// A contact set whose history is W floats per pair (the other form keeps a pool of slots for the
// pairs that have one: state/HistoryPool.h on the GPU, state/PooledHistory.h on the CPU).
constexpr size_t DENSE_HISTORY = SIZE_MAX;

// The form a contact set takes, which the bytes it needs depend on (contactSetBytes).
struct ContactSetForm {
    size_t historySlots = DENSE_HISTORY;  // its history dense, or pooled in this many slots
    size_t lateSlots = 0;                 // of them, the spare ones (DynamicsBackend::expectedLateSlots)
    // Detection is synchronous and the set in use keeps only the pairs that hand something on
    // before it (kinematics/CarriedPairsRule.h): a GPU installation then holds one whole set, not two.
    bool trimmedBeforeDetection = false;
    // Its pairs keep a persistent flag each (a model that may set one, or flags in the set it is
    // mapped from); otherwise none (both backends keep them only where used).
    bool persistentFlags = true;
};

struct MemoryEstimate {
    size_t bytes[NUM_MEMORY_GROUPS] = {};
    size_t pairs = 0;      // the contact pairs assumed
    ContactSetForm form;  // the form assumed for them
    size_t total() const {
        size_t t = 0;
        for (size_t b : bytes) t += b;
        return t;
    }
};

// onGpu: the CUDA backend's device buffers (two contact sets, history mapping's scratch, detection's
// sorted bin entries); otherwise the CPU backend's host arrays. snapshotKept: detection keeps a
// snapshot (asynchronous detection, or the GPU's kT on a second GPU; not where a synchronous
// detection reads the state in place, KinematicsBackend::detectsInPlace): each owner's travel at the
// order, and on the GPU what moves. pairs: the
// contact set's size, or ESTIMATED_PAIRS_PER_SPHERE per sphere where 0. formFor: the form of a
// first set of that many pairs (its history's from DynamicsBackend::expectedHistorySlots; dense and
// untrimmed where empty). scratchKeptUpTo: the bytes of detection scratch a synchronous detection
// in place keeps after it (keepRebuiltArraysUpTo, runtime/RebuiltArrays.h); more is let go before
// the installation.
MemoryEstimate estimateRunMemory(const SimState& s, const BinGrid& grid, bool onGpu, bool mayBinByCentre,
                                 bool snapshotKept = true, size_t pairs = 0,
                                 const std::function<ContactSetForm(size_t)>& formFor = {},
                                 size_t scratchKeptUpTo = SIZE_MAX);

// Throws a deme::Error from `call` when the estimate exceeds `available` bytes (0: not known, no
// check) of `where` ("GPU 0 (NVIDIA H200)", "host memory"), naming both and the groups. `available`
// is capped by the environment variable DEME_MEMORY_LIMIT (bytes) where set: a smaller machine, for
// tests and for runs that must leave memory to others.
void requireMemoryFor(const MemoryEstimate& e, size_t available, const std::string& where, const char* call);

// The bytes of the contacts-and-history group (the table's) for a contact set of `pairs` pairs on
// the backend whose steps keep their arrays on the GPU (onGpu) or on the host, in `form`.
size_t contactSetBytes(const SimState& s, bool onGpu, size_t pairs, const ContactSetForm& form = {});

// `available` capped by DEME_MEMORY_LIMIT where set (a deme::Error from `call` if it is not a
// number of bytes); 0 (not known) becomes the limit.
size_t memoryLimit(size_t available, const char* call);

// Before a contact set of `pairs` pairs is installed (a detection found more pairs than the run
// holds room for): throws a deme::Error from `call` naming the set, the bytes it needs (`needed`,
// contactSetBytes) and what there is, when the run, holding `held` bytes per group now, would hold
// more than `held` in all plus what `freeNow()` says is still free where the steps keep their arrays
// (0: not known, no check), capped by DEME_MEMORY_LIMIT. Nothing has changed then: the state is that
// of the last step, and the solver can still save it (WriteCheckpoint) or go on with a smaller
// margin. A set that fits what the run holds for contacts already is not checked, and the free
// memory is not asked for (a steady run asks the machine nothing).
void requireRoomForContactSet(size_t pairs, size_t needed, const size_t held[NUM_MEMORY_GROUPS],
                              const std::function<size_t()>& freeNow, const std::string& where, const char* call);

// The bytes this machine can still give (MemAvailable of /proc/meminfo; 0 where unknown).
size_t hostMemoryAvailable();

}  // namespace deme
