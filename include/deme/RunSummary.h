// What the last DoDynamics (or DoStepDynamics) call did and cost: the figures of the run summary
// printed at its end and of the benchmarks' JSON lines.
#pragma once

#include <cstddef>

namespace deme {

struct RunSummary {
    double wallSeconds = 0.0;      // of the call
    double simSeconds = 0.0;       // simulated time the call advanced
    unsigned long long steps = 0;  // steps the call took
    size_t spheres = 0;
    double sphereStepsPerSecond = 0.0;  // spheres * steps / wallSeconds
    double contactsPerSphere = 0.0;     // after the call (a sphere-sphere contact counts for both)
    size_t peakHostBytes = 0;           // the process's peak resident memory so far
    bool onGpu = false;
    size_t deviceBytes = 0, deviceBytesPeak = 0;  // GPU memory the engine holds now / held at most
};

}  // namespace deme
