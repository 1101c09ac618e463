// The memory estimate's detection bins (runtime/MemoryEstimate.h) follow how the backend registers
// the spheres: by centre where it does and the rule allows (kinematics/DetectionRules.h).
#include <gtest/gtest.h>

#include "DetectionScenes.h"
#include "kinematics/BinGridSizing.h"
#include "runtime/MemoryEstimate.h"

using namespace deme;
using namespace deme_test;

// The detection's bins as the backend registers the spheres (KinematicsBackend::
// mayBinSpheresByCentre): by centre one entry a sphere where the rule allows (bins of 4 mm for radii
// up to 2 mm), so exactly 4 bytes for each entry a box registration would make beyond the first;
// where the rule does not allow it (bins of 1.5 mm) the backend's answer changes nothing.
TEST(MemoryEstimateBins, SpheresByCentreAreOneEntryEachWhereTheBackendBinsSo) {
    const Scene scene = randomScene(3, 1500);
    SimState s = detectionState(scene, "MemoryEstimateBins");
    const size_t det = (size_t)MemoryGroup::DETECTION;
    for (bool onGpu : {false, true}) {
        const BinGrid coarse = makeBinGrid(s, 0.004), fine = makeBinGrid(s, 0.0015);
        const size_t centre = estimateRunMemory(s, coarse, onGpu, true).bytes[det];
        const size_t boxes = estimateRunMemory(s, coarse, onGpu, false).bytes[det];
        EXPECT_GT(boxes, centre + 4 * s.spheres.size()) << "on the GPU: " << onGpu;
        EXPECT_EQ(estimateRunMemory(s, fine, onGpu, true).bytes[det],
                  estimateRunMemory(s, fine, onGpu, false).bytes[det])
            << "on the GPU: " << onGpu;
    }
}
