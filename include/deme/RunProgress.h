// Where a DoDynamics call stands, as handed to the hooks polled between its steps.
#pragma once

#include <cstddef>

namespace deme {

struct RunProgress {
    unsigned long long stepsDone = 0, stepsTotal = 0;  // of this call
    double simTime = 0.0, simTimeEnd = 0.0;            // now, and where the call ends
    double wallSeconds = 0.0;                          // since the call began
    size_t spheres = 0;
    bool finished = false;  // the last poll of a call (after its last step, or when it stops early)
};

}  // namespace deme
