// Text reports of the step loop's timing and of the kinematics/dynamics collaboration.
#pragma once

#include <deme/MemoryStats.h>

#include <string>

namespace deme {

class Simulation;

std::string timingReport(const Simulation& sim);
std::string collaborationReport(const Simulation& sim);
// The table of DEMSolver::ShowMemoryStats: bytes and bytes per sphere per group, device and host.
std::string memoryReport(const MemoryStats& m);

}  // namespace deme
