// How the kinematics and dynamics sides worked together, for ShowThreadCollaborationStats().
#pragma once

namespace deme {

struct CollaborationStats {
    unsigned long long steps = 0;
    unsigned long long batches = 0;           // step batches: where the host looked between steps
    unsigned long long batchesEndedEarly = 0;  // by a step that let the set expire, or a fault
    unsigned long long acsUpdates = 0;        // contact sets installed by dynamics
    unsigned long long ordersSent = 0;        // work orders sent to kinematics
    unsigned long long dynamicsWaits = 0;     // times dynamics had to wait for (or run) a detection
    unsigned long long syncDetections = 0;    // detections run on the dynamics thread
    unsigned long long discardedResults = 0;  // results too old to use on arrival
    double dynamicsWaitSeconds = 0.0;
    double dynamicsSeconds = 0.0;    // wall time inside the step loop
    double contactSetSizeSum = 0.0;  // per step: pairs in the set
    double realContactSum = 0.0;     // per step: pairs in contact
    double latencyStepsSum = 0.0;    // per result: steps between order and arrival
};

}  // namespace deme
