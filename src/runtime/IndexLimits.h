// What 32-bit indices address. Detection's bin entries and the geometries are indexed in 32 bits
// (bodyID_t, the bins' starts), and so are the CPU's contact pairs: 4,294,967,295 of each at most (a
// GPU set's pairs in 64 bits: MAX_GPU_CONTACT_PAIRS).
// Detection counts them in 64 bits and a count past that is a deme::Error naming what overflowed,
// never a wrapped count (a wrapped total would size a set too small and lose pairs). The memory
// estimate at Initialize refuses a scene whose assumed pairs pass it (docs/memory.md).
#pragma once

#include <cstdint>

namespace deme {

constexpr uint64_t MAX_INDEXED_ITEMS = 0xFFFFFFFFull;

// Throws deme::Error naming `call` if `count` (of `what`, e.g. "contact pairs") passes
// MAX_INDEXED_ITEMS; `remedy` says what the user can change.
void requireIndexable(uint64_t count, const char* what, const char* remedy, const char* call);

// A GPU contact set indexes its pairs in 64 bits (the kernels, detection's offsets, history mapping):
// its bound is the late table's, whose entries hold a pair in 33 bits (state/HistorySlot.h).
constexpr uint64_t MAX_GPU_CONTACT_PAIRS = (1ull << 33) - 2;
// Throws deme::Error naming `call` if a GPU set's `pairs` pass MAX_GPU_CONTACT_PAIRS.
void requireGpuPairCount(uint64_t pairs, const char* call);

// The remedies for the counts detection makes.
constexpr const char* FEWER_PAIRS_REMEDY =
    "use fewer or larger grains, or a smaller margin (SetMaxVelocity, SetExpandSafetyMultiplier, "
    "SetExpandSafetyAdder)";
// At Initialize, where the pairs are assumed (6 a sphere, runtime/MemoryEstimate.h).
constexpr const char* TOO_MANY_SPHERES_REMEDY =
    "on the CPU a scene is held to about 715 million spheres by its 32-bit pair indices (docs/memory.md; a GPU "
    "run to about 1.43 billion); use fewer or larger grains";
constexpr const char* FEWER_BIN_ENTRIES_REMEDY = "use fewer grains, or bins larger than the grains (SetInitBinSize)";

}  // namespace deme
