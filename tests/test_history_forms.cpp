// A contact set's history kept for the pairs that have one only (the CPU's pool of ranked slots,
// backend/cpu/HistoryForm.h; the GPU's pool of claimed slots, state/HistoryPool.h) against W floats
// for every pair: the same trajectories to the bit. On the GPU the pool is given no spare slot
// (DEME_HISTORY_POOL_SPARE=0), so every pair that begins to touch pauses its step for the pool to
// grow and has its history made again (dynamics/PooledContactStep.h): the run must not notice.
// Every owner has at most two contacts at a time, so the GPU's atomic sums of its loads do not
// depend on their order ((0 + a) + b is (0 + b) + a), and the two forms' runs can be compared bit
// for bit there too.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "BackendFixture.h"
#include "MeshBuilders.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

namespace {

struct Pose {
    std::vector<float3> pos, vel, angVel;
};

// Spheres dropped onto a frictional floor with sideways velocities and spins, at staggered heights
// (they land at different steps), and pairs of spheres that hit each other obliquely on the way
// down; all far apart from the rest. `pooled`: the history forms that keep the pairs with a
// history only; `meshFloor`: the floor a tessellated mesh (its cells 2.5 cm across, so that rolling
// spheres cross edges and the mesh rule hands their history on) instead of a plane; `report`: the
// timing report (its launch line says how the GPU kept the history).
Pose run(bool pooled, bool meshFloor, std::string* report = nullptr) {
    const ScopedEnvironmentVariable cpuForm("DEME_CONTACT_HISTORY", pooled ? "pooled" : "dense");
    const ScopedEnvironmentVariable gpuForm("DEME_POOLED_HISTORY", pooled ? "1" : "0");
    const ScopedEnvironmentVariable spare("DEME_HISTORY_POOL_SPARE", "0");
    constexpr float R = 0.005f;
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    sim.InstructBoxDomainDimension(0.6, 0.6, 0.4);
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.4, 0.02));
    if (meshFloor)
        sim.AddWavefrontMeshObject(gridFloor(-0.3f, -0.3f, -0.15f, 24, 0.025f, mat));
    else
        sim.AddBCPlane(make_float3(0, 0, -0.15f), make_float3(0, 0, 1), mat);
    auto type = sim.LoadSphereType(0.004f, R, mat);
    std::vector<float3> pos, vel, spin;
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            const int k = 6 * i + j;
            const float x = -0.25f + 0.1f * (float)i, y = -0.25f + 0.1f * (float)j;
            if (k % 3 == 0) {
                // A pair about to collide obliquely: the upper one falls faster and is offset sideways.
                pos.push_back(make_float3(x, y, -0.1f + 0.004f * (float)(k % 5)));
                vel.push_back(make_float3(0.05f, 0, -0.2f));
                spin.push_back(make_float3(0, 20.f, 0));
                pos.push_back(make_float3(x + 0.6f * R, y + 0.5f * R, -0.1f + 0.004f * (float)(k % 5) + 2.6f * R));
                vel.push_back(make_float3(-0.05f, 0.02f, -1.0f));
                spin.push_back(make_float3(-10.f, 0, 15.f));
            } else {
                pos.push_back(make_float3(x, y, -0.15f + R + 0.0004f * (float)(k % 7)));
                vel.push_back(make_float3(0.5f * std::sin((float)k), 0.5f * std::cos((float)k), -0.3f));
                spin.push_back(make_float3(30.f * std::cos((float)k), 0, -40.f * std::sin((float)k)));
            }
        }
    auto balls = sim.AddClumps(type, pos);
    balls->SetVel(vel);
    balls->SetAngVel(spin);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetInitTimeStep(1e-5);
    sim.SetMaxVelocity(2.f);
    sim.Initialize();
    auto tr = sim.Track(balls);
    for (int call = 0; call < 4; call++) sim.DoDynamics(0.01);
    Pose p;
    for (size_t i = 0; i < pos.size(); i++) {
        p.pos.push_back(tr->Pos(i));
        p.vel.push_back(tr->Vel(i));
        p.angVel.push_back(tr->AngVelLocal(i));
    }
    if (report) {
        ::testing::internal::CaptureStdout();
        sim.ShowTimingStats();
        *report = ::testing::internal::GetCapturedStdout();
    }
    return p;
}

// `gpu`: the run is the GPU's, whose report must say that it pooled and paused.
void expectTheSameRun(bool meshFloor, bool gpu) {
    std::string report;
    const Pose dense = run(false, meshFloor), pooled = run(true, meshFloor, &report);
    size_t moved = 0;
    for (size_t i = 0; i < dense.pos.size(); i++) {
        SCOPED_TRACE(i);
        EXPECT_EQ(dense.pos[i].x, pooled.pos[i].x);
        EXPECT_EQ(dense.pos[i].y, pooled.pos[i].y);
        EXPECT_EQ(dense.pos[i].z, pooled.pos[i].z);
        EXPECT_EQ(dense.vel[i].x, pooled.vel[i].x);
        EXPECT_EQ(dense.vel[i].y, pooled.vel[i].y);
        EXPECT_EQ(dense.vel[i].z, pooled.vel[i].z);
        EXPECT_EQ(dense.angVel[i].x, pooled.angVel[i].x);
        EXPECT_EQ(dense.angVel[i].y, pooled.angVel[i].y);
        EXPECT_EQ(dense.angVel[i].z, pooled.angVel[i].z);
        // Friction has acted: every sphere is on the floor, rolling or sliding.
        moved += std::fabs(dense.angVel[i].x) + std::fabs(dense.angVel[i].y) > 1.f;
    }
    EXPECT_GT(moved, dense.pos.size() / 2);
    if (gpu) {
        // The GPU's pooled run kept every set's history pooled and paused for room (spare 0).
        EXPECT_NE(report.find("history pooled in"), std::string::npos) << report;
        EXPECT_EQ(report.find("history pooled in 0 of"), std::string::npos) << report;
        EXPECT_EQ(report.find(", 0 steps paused"), std::string::npos) << report;
    }
}

}  // namespace

DEME_BACKEND_TEST_SUITE(HistoryForms);

DEME_BACKEND_TEST(HistoryForms, PooledAndDenseHistoriesGiveTheSameRunToTheBit) { expectTheSameRun(false, onGpu()); }

// The same on a tessellated floor: sphere-triangle pairs always keep a slot in the GPU's pool, and
// the mesh rule hands a sphere's history from triangle to triangle through it.
DEME_BACKEND_TEST(HistoryForms, PooledAndDenseHistoriesGiveTheSameRunOnAMeshFloor) { expectTheSameRun(true, onGpu()); }
