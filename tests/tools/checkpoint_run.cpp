// One half of a run in a process of its own, for the test of a real restart (test_checkpoint.cpp):
//   checkpoint_run first  <checkpoint> <steps> <sync|async>          the script's first steps, then a checkpoint
//   checkpoint_run resume <checkpoint> <steps> <sync|async> <final>  the same script up to Initialize(),
//                                                                   ReadCheckpoint, more steps, a final checkpoint
// Exit status 0 on success; a deme::Error is printed and gives 1.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "CheckpointScenes.h"

int main(int argc, char** argv) {
    if (argc < 5) return 2;
    const std::string mode = argv[1], path = argv[2];
    const size_t steps = (size_t)std::atol(argv[3]);
    deme_test::CheckpointScene sc;
    sc.async = std::string(argv[4]) == "async";
    try {
        deme::DEMSolver sim;
        deme_test::buildCheckpointScene(sim, sc);
        if (mode == "first") {
            deme_test::checkpointScenePhase1(sim, sc, steps);
            sim.WriteCheckpoint(path);
        } else if (mode == "resume" && argc >= 6) {
            sim.ReadCheckpoint(path);
            for (size_t k = 0; k < steps; k++) sim.DoStepDynamics();
            sim.WriteCheckpoint(argv[5]);
        } else {
            return 2;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
