// Where a solver's memory goes, by array group (DEMSolver::GetMemoryStats, ShowMemoryStats): the
// table every change to the state's size is measured against (docs/memory.md).
#pragma once

#include <cstddef>

namespace deme {

enum class MemoryGroup : unsigned char {
    OWNER_STATE,   // owners' position, orientation, velocities, loads, family, mass properties
    GEOMETRY,      // spheres, analytical components, triangles, and their placed positions
    CONTACTS,      // the contact sets: pairs, types, per-contact history (the force model's contact
                   // wildcards, e.g. Hertz-Mindlin's tangential displacement), persistence, forces
    WILDCARDS,     // per-owner and per-geometry wildcard values of custom models
    DETECTION,     // contact detection's scratch: bins, sorted keys, pair counts, snapshots
    OUTPUT,        // output staging (frames waiting for the writer thread)
    STEP_SCRATCH,  // everything else the steps use: reductions, step subsets, control blocks
};
constexpr int NUM_MEMORY_GROUPS = 7;

// The group's name as ShowMemoryStats prints it ("owner state"), and as a key of the Python dict
// and the benchmarks' JSON ("owner_state").
const char* memoryGroupName(MemoryGroup g);
const char* memoryGroupKey(MemoryGroup g);

struct MemoryStats {
    size_t deviceBytes[NUM_MEMORY_GROUPS] = {};  // GPU memory held now (all of this process's solvers)
    // Each group's GPU memory when the process's total was last at its peak (GetDeviceMemUsage's
    // "at most"): where the peak comes from. All zero on the CPU.
    size_t devicePeakBytes[NUM_MEMORY_GROUPS] = {};
    size_t hostBytes[NUM_MEMORY_GROUPS] = {};    // host arrays of this solver (their capacities)
    // What Initialize estimated the run would hold where its steps keep their arrays (the GPU on the
    // CUDA backend, the host on the CPU's) with its first contact set of `estimatedPairs` pairs; a
    // scene whose estimate exceeds the memory there fails at Initialize (docs/memory.md).
    size_t estimatedBytes[NUM_MEMORY_GROUPS] = {};
    size_t estimatedPairs = 0;
    size_t spheres = 0;
    size_t device(MemoryGroup g) const { return deviceBytes[(int)g]; }
    size_t host(MemoryGroup g) const { return hostBytes[(int)g]; }
    size_t deviceTotal() const {
        size_t t = 0;
        for (size_t b : deviceBytes) t += b;
        return t;
    }
    size_t devicePeakTotal() const {
        size_t t = 0;
        for (size_t b : devicePeakBytes) t += b;
        return t;
    }
    size_t hostTotal() const {
        size_t t = 0;
        for (size_t b : hostBytes) t += b;
        return t;
    }
    size_t estimatedTotal() const {
        size_t t = 0;
        for (size_t b : estimatedBytes) t += b;
        return t;
    }
};

}  // namespace deme
