// DEMSolver: checkpoint and restart (io/Checkpoint.h, docs/checkpoint.md).
#include <deme/DEMSolver.h>
#include <deme/Error.h>

#include "api/Scene.h"
#include "io/Checkpoint.h"
#include "runtime/Simulation.h"

namespace deme {

void DEMSolver::WriteCheckpoint(const std::string& path) const {
    const char* call = "WriteCheckpoint";
    requireInitialized(call);
    // A waiting batch is not in the state yet: the checkpoint would lose it.
    if (!m_scene->pendingBatches.empty()) throwError(call, "clumps added by AddClumps wait for UpdateClumps()");
    writeCheckpoint(*m_sim, path, call);
}

void DEMSolver::ReadCheckpoint(const std::string& path) {
    const char* call = "ReadCheckpoint";
    requireInitialized(call);
    // Its ids were given after the state that the checkpoint replaces.
    if (!m_scene->pendingBatches.empty()) throwError(call, "clumps added by AddClumps wait for UpdateClumps()");
    readCheckpoint(*m_sim, path, call);
}

}  // namespace deme
