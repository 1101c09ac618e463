// Text reports of the step loop's timing and of the kinematics/dynamics collaboration.
#pragma once

#include <string>

namespace deme {

class Simulation;

std::string timingReport(const Simulation& sim);
std::string collaborationReport(const Simulation& sim);

}  // namespace deme
