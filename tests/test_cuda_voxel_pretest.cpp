// GPU only: the force pass's voxel pretest (dynamics/ContactStep.h) turns a sphere pair away by its
// voxel codes only where the exact test would find it apart, so a run with the pretest on for every
// set equals one with it off, bit for bit. (Whether the codes' bound holds is checked on the host,
// MathCompactPosition.VoxelCodesNeverPartAPairWithinReach; this checks the pass that uses it.)
#include <gtest/gtest.h>

#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"
#include "backend/cuda/Device.h"

using namespace deme;
using namespace deme_test;

namespace {

constexpr double DT = 2e-5;
constexpr float R = 0.005f;
constexpr int ROWS = 16, PAIRS = 8;

// Rows of sphere pairs on a floor: the two spheres of a pair overlap by 0.05 mm and push apart, and a
// pair's neighbours wait 1 mm away, inside the margin (so the set holds apart sphere pairs beside
// touching ones). A grain has at most two contacts, its partner and the floor, whose loads the GPU
// sums in either order to the same bits. The grains' positions and velocities after `steps` steps.
std::vector<float3> pairedRows(int steps) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.3, 0.4, 0.01));
    sim.InstructBoxDomainDimension(1.0, 1.0, 1.0);
    sim.AddBCPlane(make_float3(0, 0, -0.4f), make_float3(0, 0, 1), mat);
    auto type = sim.LoadSphereType((float)sphereMass(R, 2500), R, mat);
    std::vector<float3> pts;
    const float touching = 2 * R - 5e-5f, gap = 1e-3f;
    for (int i = 0; i < ROWS; i++)
        for (int j = 0; j < PAIRS; j++) {
            const float x = -0.3f + j * (touching + 2 * R + gap), y = -0.3f + 0.03f * i, z = -0.4f + R - 1e-5f;
            pts.push_back(make_float3(x, y, z));
            pts.push_back(make_float3(x + touching, y, z));
        }
    auto grains = sim.AddClumps(type, pts);
    sim.SetInitTimeStep(DT);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetExpandSafetyAdder(2e-3f);
    sim.SetCDUpdateFreq(20);
    sim.Initialize();
    auto t = sim.Track(grains);
    for (size_t k = 0; k < pts.size(); k++) t->SetAngVel(make_float3(0.f, 2.f * (float)(k % 3), 0.f), k);
    sim.DoDynamics(steps * DT);
    std::vector<float3> out;
    for (size_t k = 0; k < pts.size(); k++) {
        out.push_back(t->Pos(k));
        out.push_back(t->Vel(k));
    }
    return out;
}

}  // namespace

TEST(CudaVoxelPretest, EveryPairTestedEqualsNonePretestedBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    std::vector<float3> on, off;
    {
        ScopedEnvironmentVariable v("DEME_CUDA_VOXEL_PRETEST", "1");
        on = pairedRows(1500);
    }
    {
        ScopedEnvironmentVariable v("DEME_CUDA_VOXEL_PRETEST", "0");
        off = pairedRows(1500);
    }
    ASSERT_EQ(on.size(), off.size());
    size_t differ = 0;
    for (size_t k = 0; k < on.size(); k++)
        if (on[k].x != off[k].x || on[k].y != off[k].y || on[k].z != off[k].z) differ++;
    EXPECT_EQ(differ, 0u) << "values that differ";
    // The pairs did push apart (the run was not all at rest, which any pretest would leave alone).
    size_t moving = 0;
    for (size_t k = 1; k < off.size(); k += 2) moving += off[k].x != 0.f;
    EXPECT_GT(moving, (size_t)ROWS * PAIRS);
}
