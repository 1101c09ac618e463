// The GPU's detection in slabs of bin layers (kinematics/BinSlabs.h, runtime/DetectionSlabs.h):
// CudaKinematics, asked for 2, 3 and as many slabs as layers (DEME_DETECTION_SLABS; spheres binned
// by their centres and searched a thread each, as at scale), delivers the CPU detector's contact
// list pair for pair and in order, meshes included, at three margins. The same kernels run on the
// host in CudaDetectionKernels.SlabsFindTheCpuDetectorsPairs (CI); this one needs a GPU
// (tests/gpu/run.sh unit) and skips without one, or without the CUDA backend built.
#include <gtest/gtest.h>

#include <vector>

#ifdef DEME_TESTS_CUDA_BUILT
#include "BackendFixture.h"
#include "CudaDetectionHelpers.h"
#include "runtime/DetectionSlabs.h"

using namespace deme;
using namespace deme::cuda;
using namespace deme_test;
#endif

#ifndef DEME_TESTS_CUDA_BUILT
TEST(CudaDetectionSlabs, SlabsDeliverTheCpuDetectorsPairs) {
    GTEST_SKIP() << "the CUDA backend was not built into this library";
}
#else
TEST(CudaDetectionSlabs, SlabsDeliverTheCpuDetectorsPairs) {
    if (usableDevices().empty()) GTEST_SKIP() << "no usable GPU: " << queryDevices().whyNone;
    // Spheres by their centres, a thread a sphere, none wide: the search a scene of millions takes.
    ScopedEnvironmentVariable centre("DEME_CUDA_CENTRE_BINNING", "1");
    ScopedEnvironmentVariable lanes("DEME_CUDA_SEARCH_LANES", "1");
    ScopedEnvironmentVariable wide("DEME_CUDA_WIDE_SPHERES", "0");
    const DetectionRules dr;
    Settings settings;
    for (unsigned int f = 0; f < NUM_FAMILIES; f++) settings.familyExtraMargin[f] = dr.extra[f];
    SimState s = detectionState(randomSceneOnMeshFloor(5, 1500), "CudaDetectionSlabs");
    const BinGrid grid = makeBinGrid(s, 0.0045);
    ASSERT_GE(grid.nz, 6);
    ContactDetector cpuDet;

    useDevice("CudaDetectionSlabs", 0);
    DeviceState dev;
    dev.upload(s, nullptr);
    synchronize(nullptr);
    CudaKinematics kin(0, 0, dev, nullptr);
    kin.setGeometry(s, grid, dr.rules, settings);
    int cases = 0;
    for (int slabs : {1, 2, 3, grid.nz}) {
        ScopedEnvironmentVariable asked("DEME_DETECTION_SLABS", std::to_string(slabs));
        for (double margin : {0.0, 1e-4, 3e-4}) {
            SCOPED_TRACE(testing::Message() << slabs << " slabs of " << grid.nz << " layers, margin " << margin);
            const float largest = *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end());
            ASSERT_GT(centreReachFor(grid, margin, dr.extra, (double)largest), 0.0);
            const DetectedContacts gpu = detectOnGpu(kin, margin);
            DetectedContacts cpu;
            double binning = 0.0, search = 0.0;
            cpuDet.detect(s, grid, margin, dr.rules.contactMask(), dr.extra, cpu, binning, search);
            EXPECT_GT(cpu.size(), 500u);
            EXPECT_EQ(gpu.geomA, cpu.geomA);
            EXPECT_EQ(gpu.geomB, cpu.geomB);
            cases++;
        }
    }
    EXPECT_EQ(cases, 12);
}
#endif
