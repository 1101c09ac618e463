// The interrupt check polled between steps (SetInterruptCheck): it stops a DoDynamics call at a
// step boundary, and the run goes on from there as if it had never stopped.
//
// Tolerance: none on the CPU. A call stopped after k steps and a second call of the remaining
// steps take exactly the steps one call takes (the step loop has no per-call state but tracker
// loads), so the trajectory is bit-identical.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

namespace {

struct Bed {
    DEMSolver sim;
    std::shared_ptr<DEMClumpBatch> grains;
    Bed() {
        // CPU only: the check is bit for bit, which holds where each owner sums its contacts in a
        // fixed order (the CPU); the GPU's atomics sum in no fixed order, so two GPU runs differ.
        sim.SetBackend("cpu");
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.4, 0.5, 0.01));
        sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.4f);
        sim.InstructBoxDomainBoundingBC("top_open", mat);
        auto pts = HCPSampler(0.0082f).SampleBox(make_float3(0, 0, -0.15f), make_float3(0.05f, 0.05f, 0.03f));
        grains = sim.AddClumps(sim.LoadSphereType((float)sphereMass(0.004, 2600), 0.004f, mat), pts);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
        sim.SetInitTimeStep(1e-5);
        sim.SetSynchronousContactDetection(true);
        sim.Initialize();
    }
    std::vector<float> positions() {
        auto tr = sim.Track(grains);
        std::vector<float> out;
        for (size_t i = 0; i < tr->GetNumOwners(); i++) {
            const float3 p = tr->Pos(i), v = tr->Vel(i);
            out.insert(out.end(), {p.x, p.y, p.z, v.x, v.y, v.z});
        }
        return out;
    }
};

}  // namespace

TEST(RunMonitor, InterruptStopsAtAStepBoundaryAndTheRunGoesOn) {
    const double total = 0.05;  // 5000 steps: several polls' worth of wall time on any machine
    Bed straight;
    straight.sim.DoDynamics(total);
    EXPECT_FALSE(straight.sim.WasInterrupted());

    Bed stopped;
    int checks = 0;
    stopped.sim.SetInterruptCheck([&checks] { return ++checks == 1; });
    const auto t0 = std::chrono::steady_clock::now();
    stopped.sim.DoDynamics(total);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(stopped.sim.WasInterrupted());
    EXPECT_EQ(checks, 1);
    const double reached = stopped.sim.GetSimTime();
    EXPECT_GT(reached, 0.0);
    EXPECT_LT(reached, total);
    // A whole number of steps, and soon after the first poll (50 ms): well under the whole call.
    const double steps = reached / 1e-5;
    EXPECT_NEAR(steps, std::round(steps), 1e-6);
    EXPECT_LT(wall, 5.0);

    stopped.sim.SetInterruptCheck(nullptr);
    stopped.sim.DoDynamics(total - reached);
    EXPECT_FALSE(stopped.sim.WasInterrupted());
    EXPECT_NEAR(stopped.sim.GetSimTime(), total, 1e-9);
    EXPECT_EQ(stopped.positions(), straight.positions());
}

TEST(RunMonitor, ACheckThatNeverFiresChangesNothing) {
    Bed plain, watched;
    int checks = 0;
    watched.sim.SetInterruptCheck([&checks] {
        checks++;
        return false;
    });
    plain.sim.DoDynamics(0.03);
    watched.sim.DoDynamics(0.03);
    EXPECT_FALSE(watched.sim.WasInterrupted());
    EXPECT_NEAR(watched.sim.GetSimTime(), 0.03, 1e-9);
    EXPECT_EQ(watched.positions(), plain.positions());
}
