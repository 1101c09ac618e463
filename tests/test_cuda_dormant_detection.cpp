// The active box on the GPU (docs/active-box.md): CudaKinematics with a dormant family builds the
// dormant registry on the device once, bins and searches the moving spheres only, and delivers the
// CPU's cached detector's contact list (backend/cpu/DormantCache.h, checked against brute force by
// ActiveBoxDetection.DormantCacheFindsExactlyTheFullSearchsPairs) pair for pair and in order; a
// family change rebuilds the registry once, and a wall that moves makes it search everything. The
// same kernels run on the host in CudaDetectionKernels.DormantRegistryMatchesTheCpuCachedDetectorExactly
// (CI); this one needs a GPU (tests/gpu/run.sh unit) and skips without one, or without the CUDA
// backend built (CudaKinematics exists only then).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#ifdef DEME_TESTS_CUDA_BUILT
#include "CudaDetectionHelpers.h"

using namespace deme;
using namespace deme::cuda;
using namespace deme_test;

#endif

#ifndef DEME_TESTS_CUDA_BUILT
TEST(CudaDormantDetection, MatchesTheCpuCachedDetectorPairForPair) {
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

    useDevice("CudaDormantDetection", 0);
    DeviceState dev;
    dev.upload(s, nullptr);
    synchronize(nullptr);
    CudaKinematics kin(0, 0, dev, nullptr);
    kin.setGeometry(s, grid, rules, settings);

    auto compare = [&](double margin) {
        SCOPED_TRACE(testing::Message() << "margin " << margin);
        const DetectedContacts gpu = detectOnGpu(kin, margin);
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
    dev.owners.family.uploadAsync(s.owners.family.data(), s.owners.family.size(), nullptr);
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
