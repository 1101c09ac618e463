// One step of the dynamics side as a CUDA graph, replayed for every step of a batch: a step is a
// handful of small kernels, and at lab scale (10^4-10^5 grains) launching them one by one costs
// more than running them. The graph is made from the step's launch list (LaunchList.h) by stream
// capture and kept while the list stays the same; when it changes (a new contact set, a grown
// array, a recompiled prescription), the graph is updated in place where CUDA allows, or made anew.
// A graph may hold several replays of the list one after the other (`repeats`): every graph launch
// and the gap after it cost the GPU a few microseconds, as much as a small kernel, so a batch queues
// its steps in graphs of several steps (CudaStepBatch.cpp). Kernels that find the batch ended return
// at once, so a step queued past the batch's end does nothing, as with one graph per step.
// DEME_CUDA_GRAPHS=0 launches the lists directly instead (docs/cuda-backend.md).
#pragma once

#include <cstdlib>
#include <string>

#include <deme/Error.h>

#include "backend/cuda/CudaTypes.h"
#include "backend/cuda/LaunchList.h"

namespace deme::cuda {

class StepGraph {
  public:
    StepGraph() = default;
    ~StepGraph();
    StepGraph(const StepGraph&) = delete;
    StepGraph& operator=(const StepGraph&) = delete;

    // Queues `list` on `stream` `repeats` times in a row, through the graph made from as many
    // copies of it.
    void launch(const LaunchList& list, Stream stream, unsigned int repeats = 1);
    // Graphs made (captures) and updated in place so far, for the timing report and tests.
    unsigned long long captures() const { return m_captures; }
    unsigned long long updates() const { return m_updates; }

  private:
    void make(const LaunchList& list, Stream stream, unsigned int repeats);

    LaunchList m_made;           // the list the graph was made from
    unsigned int m_repeats = 0;  // and how many copies of it it holds
    void* m_exec = nullptr;      // a cudaGraphExec_t
    unsigned long long m_captures = 0, m_updates = 0;
};

// Whether step graphs are used (DEME_CUDA_GRAPHS unset or not "0").
bool stepGraphsEnabled();
// Whether a step's kernels may overlap the drain of the kernel before them where the GPU allows it
// (compute capability 9.0+; LaunchList::overlapLaunches): DEME_CUDA_OVERLAP_LAUNCHES unset or not "0".
bool overlappedLaunchesEnabled();
// Whether a step of a scene without triangles integrates and places in one kernel
// (deme_integrate_and_place): DEME_CUDA_FUSED_STEP unset or not "0".
bool fusedStepEnabled();
// Whether that kernel's block that steps every analytical owner places their components (rather
// than the block that finishes last): DEME_CUDA_ANALYTICAL_IN_BLOCK unset or not "0".
bool analyticalInBlockEnabled();
// Whether an owner step right after a force pass reads its inputs (all but the loads) before it
// waits for that pass (kernels/Dynamics.cu, startOwnerStep): DEME_CUDA_INPUTS_BEFORE_WAIT unset or
// not "0".
bool inputsBeforeWaitEnabled();
// Whether integration clears the loads it read for a scene of `owners` owners (instead of a kernel
// at the start of every step): DEME_CUDA_LOADS_CLEARED_BY_INTEGRATION "1" or "0", or by default for
// scenes under 2^18 owners, where a step's kernels are latency bound and one fewer is worth 2-3 %
// on the drum; above, where a step is bandwidth bound, the kernel stays (at 2.9 M spheres one H200
// was 4 % slower without it, another as fast: BENCHMARKS.md, SMALL-SYSTEMS).
bool loadsClearedByIntegration(unsigned int owners);
// How many steps one graph launch queues (DEME_CUDA_GRAPH_STEPS, default 8; 1 is a graph per step).
// Inline, without CUDA: a library built without the backend parses (and tests) it the same way.
inline unsigned int stepsPerGraph() {
    const char* v = std::getenv("DEME_CUDA_GRAPH_STEPS");
    if (!v || !*v) return 8;
    char* end = nullptr;
    const unsigned long n = std::strtoul(v, &end, 10);
    if (*end || n < 1 || n > 256)
        throwError("Initialize", std::string("DEME_CUDA_GRAPH_STEPS is '") + v + "', not a whole number from 1 to 256");
    return (unsigned int)n;
}

}  // namespace deme::cuda
