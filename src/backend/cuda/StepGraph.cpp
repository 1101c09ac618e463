#include "backend/cuda/StepGraph.h"

#include <cstdlib>
#include <cstring>

#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"

namespace deme::cuda {

namespace {
constexpr const char* CALL = "DoDynamics";

// A diagnostic switch that is on unless the variable is "0".
bool onUnlessZero(const char* variable) {
    const char* v = std::getenv(variable);
    return !(v && std::strcmp(v, "0") == 0);
}
}  // namespace

bool stepGraphsEnabled() { return onUnlessZero("DEME_CUDA_GRAPHS"); }

bool overlappedLaunchesEnabled() { return onUnlessZero("DEME_CUDA_OVERLAP_LAUNCHES"); }

bool fusedStepEnabled() { return onUnlessZero("DEME_CUDA_FUSED_STEP"); }

bool analyticalInBlockEnabled() { return onUnlessZero("DEME_CUDA_ANALYTICAL_IN_BLOCK"); }

bool inputsBeforeWaitEnabled() { return onUnlessZero("DEME_CUDA_INPUTS_BEFORE_WAIT"); }

bool loadsClearedByIntegration(unsigned int owners) {
    const char* v = std::getenv("DEME_CUDA_LOADS_CLEARED_BY_INTEGRATION");
    if (v && *v) return std::strcmp(v, "0") != 0;
    return owners < (1u << 18);
}

StepGraph::~StepGraph() {
    if (m_exec && cudaGraphExecDestroy(static_cast<cudaGraphExec_t>(m_exec)) != cudaSuccess) cudaGetLastError();
}

void StepGraph::make(const LaunchList& list, Stream stream, unsigned int repeats) {
    cudaStream_t st = static_cast<cudaStream_t>(stream);
    // Thread-local capture: the kinematics thread goes on using the GPU meanwhile.
    DEME_CUDA_CHECK(CALL, cudaStreamBeginCapture(st, cudaStreamCaptureModeThreadLocal));
    cudaGraph_t graph = nullptr;
    try {
        for (unsigned int r = 0; r < repeats; r++) list.enqueue(stream);
    } catch (...) {
        if (cudaStreamEndCapture(st, &graph) == cudaSuccess && graph) cudaGraphDestroy(graph);
        cudaGetLastError();
        throw;
    }
    DEME_CUDA_CHECK(CALL, cudaStreamEndCapture(st, &graph));
    bool updated = false;
    if (m_exec) {
        cudaGraphExecUpdateResultInfo info{};
        if (cudaGraphExecUpdate(static_cast<cudaGraphExec_t>(m_exec), graph, &info) == cudaSuccess) {
            updated = true;
            m_updates++;
        } else {
            cudaGetLastError();  // another shape of graph (a kernel more or less): made anew below
            cudaGraphExecDestroy(static_cast<cudaGraphExec_t>(m_exec));
            m_exec = nullptr;
        }
    }
    if (!updated) {
        cudaGraphExec_t exec = nullptr;
        const cudaError_t e = cudaGraphInstantiate(&exec, graph, 0);
        cudaGraphDestroy(graph);
        DEME_CUDA_CHECK(CALL, e);
        m_exec = exec;
    } else {
        cudaGraphDestroy(graph);
    }
    m_captures++;
    m_made = list;
    m_repeats = repeats;
}

void StepGraph::launch(const LaunchList& list, Stream stream, unsigned int repeats) {
    if (list.empty() || repeats == 0) return;
    if (!m_exec || repeats != m_repeats || list != m_made) make(list, stream, repeats);
    DEME_CUDA_CHECK(CALL, cudaGraphLaunch(static_cast<cudaGraphExec_t>(m_exec), static_cast<cudaStream_t>(stream)));
}

}  // namespace deme::cuda
