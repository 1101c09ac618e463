// CudaKinematics on a GPU against the CPU's detectors, pair for pair and in order (white-box tests of
// the CUDA backend; they need a GPU, tests/gpu/run.sh unit, and skip without one, or without the
// CUDA backend built, as CudaKinematics exists only then). The same kernels run on the host in
// CudaDetectionKernels.* (CI).
// - The active box (docs/active-box.md): with a dormant family CudaKinematics builds the dormant
//   registry on the device once, bins and searches the moving spheres only, and delivers the CPU's
//   cached detector's list (backend/cpu/DormantCache.h, checked against brute force by
//   ActiveBoxDetection.DormantCacheFindsExactlyTheFullSearchsPairs); a family change rebuilds the
//   registry once, and a wall that moves makes it search everything.
// - Detection in slabs of bin layers (kinematics/BinSlabs.h, runtime/DetectionSlabs.h): asked for
//   1, 2, 3 and as many slabs as layers (spheres binned by their centres and searched a thread each,
//   as at scale), it delivers the CPU detector's list, meshes included, at three margins.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#ifdef DEME_TESTS_CUDA_BUILT
#include "BackendFixture.h"
#include "DetectionScenes.h"
#include "backend/cpu/ContactDetector.h"
#include "backend/cuda/CudaKinematics.h"
#include "backend/cuda/Device.h"
#include "kinematics/BinGridSizing.h"
#include "runtime/DetectionSlabs.h"
#include "runtime/FamilyRules.h"
#include "runtime/Settings.h"

using namespace deme;
using namespace deme::cuda;
using namespace deme_test;

namespace {

// A scene's state on GPU 0 and CudaKinematics over it, its geometry set.
struct GpuDetector {
    DeviceState dev;
    std::unique_ptr<CudaKinematics> kin;
    GpuDetector(const SimState& s, const BinGrid& grid, const FamilyRules& rules, const Settings& settings,
                const char* call) {
        useDevice(call, 0);
        dev.upload(s, nullptr);
        synchronize(nullptr);
        kin = std::make_unique<CudaKinematics>(0, 0, dev, nullptr);
        kin->setGeometry(s, grid, rules, settings);
    }
    // A synchronous detection with margin `margin`, the outbox's pairs downloaded.
    DetectedContacts detect(double margin) {
        DetectionOrder order;
        order.margin = margin;
        DetectionReport report;
        kin->detectNow(order, report);
        const size_t n = report.numPairs;
        DetectedContacts gpu;
        gpu.geomB.resize(n);
        if (n) kin->outbox().geomB.downloadAsync(gpu.geomB.data(), n, nullptr);
        downloadPairAs(kin->outbox().pairA, n, gpu.geomA, nullptr);  // waits
        return gpu;
    }
};

}  // namespace
#endif

#ifndef DEME_TESTS_CUDA_BUILT
TEST(CudaDormantDetection, MatchesTheCpuCachedDetectorPairForPair) {
    GTEST_SKIP() << "the CUDA backend was not built into this library";
}
TEST(CudaDetectionSlabs, SlabsDeliverTheCpuDetectorsPairs) {
    GTEST_SKIP() << "the CUDA backend was not built into this library";
}
#else
TEST(CudaDormantDetection, MatchesTheCpuCachedDetectorPairForPair) {
    if (usableDevices().empty()) GTEST_SKIP() << "no usable GPU: " << queryDevices().whyNone;
    FamilyRules rules;
    rules.motion(2).fixed = true;   // family 2 is dormant: fixed, ...
    rules.setContact(2, 2, false);  // ... no contacts among its grains
    Settings settings;
    settings.familyExtraMargin[1] = 2e-4f;
    settings.familyExtraMargin[2] = 1e-4f;  // dormant grains reach further
    const float* extra = settings.familyExtraMargin;
    uint8_t dormant[NUM_FAMILIES], prescribed[NUM_FAMILIES];
    rules.dormantFamilies(dormant);
    rules.prescribedFamilies(prescribed);
    ASSERT_EQ(dormant[2], 1);

    SimState s = detectionState(randomSceneOnMeshFloor(3, 1500), "CudaDormantDetection");
    const BinGrid grid = makeBinGrid(s, 0.0015);
    ContactDetector cpuDet;
    cpuDet.setFamilies(dormant, prescribed, s);

    GpuDetector gpuDet(s, grid, rules, settings, "CudaDormantDetection");
    CudaKinematics& kin = *gpuDet.kin;

    auto compare = [&](double margin) {
        SCOPED_TRACE(testing::Message() << "margin " << margin);
        const DetectedContacts gpu = gpuDet.detect(margin);
        DetectedContacts cpu;
        double binning = 0.0, search = 0.0;
        cpuDet.detect(s, grid, margin, rules.contactMask(), extra, cpu, binning, search);
        EXPECT_GT(cpu.size(), 500u);
        EXPECT_EQ(gpu.geomA, cpu.geomA);
        EXPECT_EQ(gpu.geomB, cpu.geomB);
    };
    for (double margin : {0.0, 1e-4, 3e-4}) compare(margin);
    EXPECT_EQ(kin.dormantRegistryRebuilds(), 1u);  // built once for three margins
    EXPECT_EQ(cpuDet.dormantCache().rebuilds(), 1u);

    // A grain wakes up, another falls dormant (the snapshot reads the device's families).
    ASSERT_TRUE(wakeOneAndFreezeOne(s, 2, 0));
    gpuDet.dev.owners.family.uploadAsync(s.owners.family.data(), s.owners.family.size(), nullptr);
    synchronize(nullptr);
    compare(2e-4);
    compare(1e-4);
    EXPECT_EQ(kin.dormantRegistryRebuilds(), 2u);  // once for the change

    // A wall that moves and reaches dormant grains: everything searched, no registry built.
    s.owners.vel[s.analytical.owner[0]] = make_float3(0, 0, 0.1f);
    cpuDet.setFamilies(dormant, prescribed, s);
    kin.setGeometry(s, grid, rules, settings);
    compare(1e-4);
    EXPECT_EQ(kin.dormantRegistryRebuilds(), 2u);
}

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

    GpuDetector gpuDet(s, grid, dr.rules, settings, "CudaDetectionSlabs");
    int cases = 0;
    for (int slabs : {1, 2, 3, grid.nz}) {
        ScopedEnvironmentVariable asked("DEME_DETECTION_SLABS", std::to_string(slabs));
        for (double margin : {0.0, 1e-4, 3e-4}) {
            SCOPED_TRACE(testing::Message() << slabs << " slabs of " << grid.nz << " layers, margin " << margin);
            const float largest = *std::max_element(s.spheres.radius.begin(), s.spheres.radius.end());
            ASSERT_GT(centreReachFor(grid, margin, dr.extra, (double)largest), 0.0);
            const DetectedContacts gpu = gpuDet.detect(margin);
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

#ifdef DEME_TESTS_CUDA_BUILT
// Which walls and meshes can move (a byte per owner, on the host and on the GPU) is kept only for a
// registry: a run without dormant families holds none of it (the early mixer's 1 B/sphere of
// detection scratch, docs/memory.md). No GPU needed.
TEST(CudaDormantDetection, WallsThatMoveAreListedOnlyWithDormantFamilies) {
    Scene scene = randomScene(3, 200);
    auto floor =
        std::make_shared<DEMMeshConnected>(gridFloor(-0.02f, -0.02f, -0.015f, 4, 0.01f, scene.materials.front()));
    floor->SetFamily(1);
    scene.meshes.push_back(floor);
    const SimState s = detectionState(scene, "CudaDormantDetection");
    FamilyRules rules;
    const DormantFamilies none = DormantFamilies::of(s, rules);
    EXPECT_FALSE(none.any);
    EXPECT_TRUE(none.movable.empty());
    rules.motion(2).fixed = true;  // family 2 dormant
    rules.setContact(2, 2, false);
    const DormantFamilies some = DormantFamilies::of(s, rules);
    EXPECT_TRUE(some.any);
    EXPECT_EQ(some.movable.size(), s.owners.size());
}
#endif
