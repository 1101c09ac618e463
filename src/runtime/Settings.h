// User-set run parameters, validated by DEMSolver and read by the simulation.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <deme/VectorTypes.h>

namespace deme {

enum class Verbosity { QUIET = 0, ERROR = 1, WARNING = 2, INFO = 3, STEP_METRIC = 4 };

struct Settings {
    double dt = -1.0;  // must be set
    float3 gravity = make_float3(0.f, 0.f, 0.f);
    float errorOutVelocity = 1e30f;
    float maxVelocity = 0.f;        // user's expected largest speed (0: measured only)
    float safetyMultiplier = 1.1f;  // margin = multiplier * vmax * dt * n + adder
    float safetyAdder = 0.f;
    // The largest margin a detection may use: periodic boundaries keep every interaction within half
    // a period (runtime/PeriodicLimits.h); unbounded otherwise. Set by the simulation.
    double maxMargin = std::numeric_limits<double>::infinity();
    unsigned int updateFreq = 20;      // initial (or fixed) n_max: steps one contact set may serve
    unsigned int maxUpdateFreq = 200;  // cap for the adaptive n_max
    bool adaptiveUpdateFreq = true;
    // Contact detection on a kinematics thread beside the dynamics (async) or on the dynamics thread
    // (sync). AUTO picks async where the CPU has cores to spare for it (docs/threads.md).
    enum class DetectionMode { AUTO, SYNC, ASYNC } detectionMode = DetectionMode::AUTO;
    bool asyncDetection = false;        // the mode in effect
    int kinematicsThreads = 1;          // OpenMP threads of the kinematics thread's loops
    float familyExtraMargin[256] = {};  // added to the margin of each family's geometries
    double binSize = 0.0;               // 0: chosen at Initialize
    unsigned int threadsPerBlock = 0;  // the GPU force pass's blocks; 0: by the set's size (stepThreadsFor)
    unsigned int cpuThreads = 0;  // 0: OpenMP default
    // Where the step loop runs: "cpu", "cuda" or "auto" (CUDA where a usable GPU is present); the
    // DEME_BACKEND environment variable, if set, is the default. deviceIds: the GPUs to use.
    std::string backend;
    std::vector<int> deviceIds;
    bool onGpu = false;  // the backend in effect
    Verbosity verbosity = Verbosity::INFO;
    // Sphere file columns beyond X,Y,Z,r.
    bool outAbsv = false, outVel = false, outAngVel = false, outFamily = false, outOwner = false, outMat = false,
         outQuat = false;
    bool outOwnerWildcards = false;  // sphere and clump files: one column per owner wildcard
    // The domain exit policy (SetDomainExitPolicy): a clump leaving the domain stops the run
    // ("error", false) or is removed at the step it leaves ("remove", true).
    bool removeLeavingClumps = false;
};

}  // namespace deme
