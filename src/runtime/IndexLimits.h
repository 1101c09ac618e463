// What 32-bit indices address. A contact set's pairs, detection's bin entries and the geometries
// are indexed in 32 bits (bodyID_t, the sets' offsets and slots): 4,294,967,295 of each at most.
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

// The remedies for the counts detection makes.
constexpr const char* FEWER_PAIRS_REMEDY =
    "use fewer or larger grains, or a smaller margin (SetMaxVelocity, SetExpandSafetyMultiplier, "
    "SetExpandSafetyAdder)";
// At Initialize, where the pairs are assumed (6 a sphere, runtime/MemoryEstimate.h).
constexpr const char* TOO_MANY_SPHERES_REMEDY =
    "a scene is held to about 715 million spheres by its 32-bit pair indices (docs/memory.md); use fewer or "
    "larger grains";
constexpr const char* FEWER_BIN_ENTRIES_REMEDY = "use fewer grains, or bins larger than the grains (SetInitBinSize)";

}  // namespace deme
