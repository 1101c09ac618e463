// DEMSolver: checkpoint and restart (io/Checkpoint.h, docs/checkpoint.md).
#include <deme/DEMSolver.h>

#include "io/Checkpoint.h"
#include "runtime/Simulation.h"

namespace deme {

void DEMSolver::WriteCheckpoint(const std::string& path) const {
    const char* call = "WriteCheckpoint";
    requireInitialized(call);
    writeCheckpoint(*m_sim, path, call);
}

void DEMSolver::ReadCheckpoint(const std::string& path) {
    const char* call = "ReadCheckpoint";
    requireInitialized(call);
    readCheckpoint(*m_sim, path, call);
}

}  // namespace deme
