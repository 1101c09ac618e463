// Steps run in batches (dynamics/StepBatch.h): the host looks only between batches, and a batch ends
// early after a step that lets the contact set in use expire or faults. None of that may show in the
// trajectory: a run of N steps in one call equals N calls of one step, bit for bit, on every backend
// (the scene gives each grain at most one contact, the floor, so that the GPU's atomic sums have one
// term and are exact), and the step clock that prescribed motion reads advances within a batch.
// On a GPU the batch's steps are replays of captured steps, several to a graph (backend/cuda/StepGraph.h);
// they must equal the same kernels launched one by one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "BackendFixture.h"
#include "TestHelpers.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/StepGraph.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(StepBatches);

namespace {

constexpr double DT = 2e-5;
constexpr float R = 0.005f;

struct Trajectory {
    std::vector<float3> pos, vel, angVel;
    double time = 0.0;
};

// 64 spheres dropped together from rest onto a floor, far enough apart never to touch each other,
// with a little spin and sideways speed (friction and rolling resistance act), all pulled down at
// 500 m/s^2 more than gravity (a tracker load, which the margin does not foresee): whenever they
// start falling from rest (at the start, at each apex of their bounces) their contact sets expire by
// travel before n_max, in the middle of a batch. One more sphere, in family 3, far from the others,
// is carried sideways at vx = 0.3 t.
struct BouncingSpheres {
    DEMSolver sim;
    std::shared_ptr<DEMClumpBatch> grains, carried;
    std::shared_ptr<DEMTracker> tracker, carriedTracker;

    explicit BouncingSpheres(bool async) {
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.9, 0.4, 0.02));
        sim.InstructBoxDomainDimension(1.0, 1.0, 1.0);
        sim.AddBCPlane(make_float3(0, 0, -0.4f), make_float3(0, 0, 1), mat);
        auto type = sim.LoadSphereType((float)sphereMass(R, 2500), R, mat);
        std::vector<float3> pts;
        for (int i = 0; i < 8; i++)
            for (int j = 0; j < 8; j++)
                pts.push_back(make_float3(-0.35f + 0.1f * i, -0.35f + 0.1f * j, -0.4f + R + 0.01f));
        grains = sim.AddClumps(type, pts);
        carried = sim.AddClumps(type, {make_float3(-0.3f, 0.4f, 0.3f)});
        carried->SetFamily(3);
        sim.SetFamilyPrescribedLinVel(3, "0.3 * t", "0", "0");
        sim.SetInitTimeStep(DT);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
        sim.SetCDUpdateFreq(30);
        sim.SetSynchronousContactDetection(!async);
        sim.Initialize();
        tracker = sim.Track(grains);
        carriedTracker = sim.Track(carried);
        for (size_t k = 0; k < pts.size(); k++) {
            tracker->SetVel(make_float3(0.002f * (float)(k % 5), -0.001f * (float)(k % 3), 0.f), k);
            tracker->SetAngVel(make_float3(0.5f * (float)(k % 7), 0.f, -0.3f * (float)(k % 2)), k);
        }
    }

    // The extra pull, for the next call.
    void pull() {
        for (size_t k = 0; k < 64; k++) tracker->AddAcc(make_float3(0, 0, -500.f), k);
    }

    Trajectory state() const {
        Trajectory t;
        for (size_t k = 0; k < 64; k++) {
            t.pos.push_back(tracker->Pos(k));
            t.vel.push_back(tracker->Vel(k));
            t.angVel.push_back(tracker->AngVelGlobal(k));
        }
        t.pos.push_back(carriedTracker->Pos());
        t.vel.push_back(carriedTracker->Vel());
        t.angVel.push_back(carriedTracker->AngVelGlobal());
        t.time = sim.GetSimTime();
        return t;
    }
};

bool same(const float3& a, const float3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

void expectBitForBit(const Trajectory& a, const Trajectory& b) {
    ASSERT_EQ(a.pos.size(), b.pos.size());
    EXPECT_EQ(a.time, b.time);
    size_t differ = 0;
    for (size_t k = 0; k < a.pos.size(); k++)
        if (!same(a.pos[k], b.pos[k]) || !same(a.vel[k], b.vel[k]) || !same(a.angVel[k], b.angVel[k])) differ++;
    EXPECT_EQ(differ, 0u) << "grains whose state differs";
}

constexpr int STEPS = 3000;

Trajectory inOneCall(bool async, unsigned long long* endedEarly = nullptr) {
    BouncingSpheres s(async);
    s.pull();
    s.sim.DoDynamics(STEPS * DT);
    if (endedEarly) *endedEarly = batchesEndedEarly(s.sim);
    return s.state();
}

Trajectory stepByStep(bool async) {
    BouncingSpheres s(async);
    for (int k = 0; k < STEPS; k++) {
        s.pull();
        s.sim.DoStepDynamics();
    }
    return s.state();
}

}  // namespace

// Batches of up to 30 steps (n_max), many ended early by travel, against a host that looks after
// every step; synchronous detection, then asynchronous (whose sets arrive at other steps, which the
// trajectory does not depend on).
DEME_BACKEND_TEST(StepBatches, OneCallEqualsStepByStepBitForBit) {
    for (bool async : {false, true}) {
        SCOPED_TRACE(async ? "asynchronous detection" : "synchronous detection");
        unsigned long long endedEarly = 0;
        const Trajectory one = inOneCall(async, &endedEarly);
        EXPECT_GT(endedEarly, 10u);
        // The floor held them: without it they would have fallen 0.9 m by now.
        for (size_t k = 0; k < 64; k++) EXPECT_GT(one.pos[k].z, -0.4f + 0.9f * R);
        expectBitForBit(one, stepByStep(async));
    }
}

// The clock that prescribed motion reads advances with every step of a batch: the carried sphere's
// velocity at the end of step n is 0.3 (n + 1) dt, so after N steps it has moved
// 0.3 dt^2 N (N + 1) / 2. A clock held at the batch's start would leave it up to a batch behind
// (0.3 x 30 dt x dt per step: 2e-4 of the distance here).
DEME_BACKEND_TEST(StepBatches, PrescribedMotionReadsTheClockOfEachStep) {
    BouncingSpheres s(false);
    const float3 x0 = s.carriedTracker->Pos();
    s.sim.DoDynamics(STEPS * DT);
    const double n = STEPS;
    const double expected = 0.3 * DT * DT * n * (n + 1) / 2;
    EXPECT_NEAR(s.carriedTracker->Pos().x - x0.x, expected, 1e-6 * expected + 1e-7);
    EXPECT_NEAR(s.carriedTracker->Vel().x, 0.3 * n * DT, 1e-6);
    EXPECT_NEAR(s.sim.GetSimTime(), n * DT, 1e-12);
}

// GPU only: a batch replayed from a captured step graph equals the same kernels launched one by one
// (DEME_CUDA_GRAPHS=0), bit for bit.
TEST(CudaStepGraphs, ReplayEqualsDirectLaunchesBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    Trajectory graphs, direct;
    {
        ScopedEnvironmentVariable on("DEME_CUDA_GRAPHS", "1");
        graphs = inOneCall(false);
    }
    {
        ScopedEnvironmentVariable off("DEME_CUDA_GRAPHS", "0");
        direct = inOneCall(false);
    }
    expectBitForBit(graphs, direct);
}

// GPU only: a step's kernels launched to overlap the drain of the kernel before them (programmatic
// dependent launch, kernels/DependentLaunch.cuh; the default on GPUs of compute capability 9.0+)
// give the trajectory of kernels that start only once the one before has ended, bit for bit; with
// graphs and without. A kernel that read its predecessor's results before waiting would see some
// of them stale and drift from it.
TEST(CudaStepGraphs, OverlappedLaunchesEqualSerialLaunchesBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    for (const char* graphs : {"1", "0"}) {
        SCOPED_TRACE(std::string("DEME_CUDA_GRAPHS=") + graphs);
        ScopedEnvironmentVariable g("DEME_CUDA_GRAPHS", graphs);
        Trajectory serial;
        {
            ScopedEnvironmentVariable off("DEME_CUDA_OVERLAP_LAUNCHES", "0");
            serial = inOneCall(false);
        }
        ScopedEnvironmentVariable on("DEME_CUDA_OVERLAP_LAUNCHES", "1");
        expectBitForBit(inOneCall(false), serial);
    }
}

// Dumbbells (two spheres off their owner's centre: placement rotates them) dropped spinning onto a
// plane, far enough apart never to touch each other: an owner has at most two contacts, whose loads
// the GPU sums in either order to the same bits (three or more would make the sum's order, and so
// the trajectory, vary from run to run). Their poses after `steps` steps.
std::vector<float4> fallingDumbbellPoses(int steps) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.4, 0.01));
    sim.InstructBoxDomainDimension(0.4, 0.4, 0.4);
    sim.AddBCPlane(make_float3(0, 0, -0.15f), make_float3(0, 0, 1), mat);
    const float r = 0.006f, m = (float)sphereMass(r, 2500) * 2.f, I = 0.4f * m * r * r + m * r * r;
    auto dumbbell = sim.LoadClumpType(m, make_float3(0.4f * m * r * r, I, I), {r, r},
                                      {make_float3(r, 0, 0), make_float3(-r, 0, 0)}, mat);
    std::vector<float3> pts;
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) pts.push_back(make_float3(-0.15f + 0.06f * i, -0.15f + 0.06f * j, -0.12f));
    auto batch = sim.AddClumps(dumbbell, pts);
    sim.SetInitTimeStep(DT);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    auto t = sim.Track(batch);
    for (size_t k = 0; k < pts.size(); k++) t->SetAngVel(make_float3(3.f * (float)(k % 5), 2.f, -1.f * (float)(k % 3)), k);
    sim.DoDynamics(steps * DT);
    std::vector<float4> poses;
    for (size_t k = 0; k < pts.size(); k++) {
        const float3 p = t->Pos(k);
        poses.push_back(make_float4(p.x, p.y, p.z, 0.f));
        poses.push_back(t->OriQ(k));
    }
    return poses;
}

namespace {

// The bouncing spheres (a prescribed family, tracker loads, batches ended early) and dumbbells that
// spin and land on a plane, with the switch `variable` "0" and then "1": the same trajectories, bit
// for bit. Returns the dumbbells' poses.
std::vector<float4> expectTheSameWhether(const char* variable) {
    Trajectory off;
    std::vector<float4> clumpsOff;
    {
        ScopedEnvironmentVariable v(variable, "0");
        off = inOneCall(false);
        clumpsOff = fallingDumbbellPoses(6000);
    }
    ScopedEnvironmentVariable v(variable, "1");
    expectBitForBit(inOneCall(false), off);
    const std::vector<float4> on = fallingDumbbellPoses(6000);
    EXPECT_EQ(on.size(), clumpsOff.size());
    size_t differ = 0;
    for (size_t k = 0; k < on.size() && k < clumpsOff.size(); k++)
        differ += on[k].x != clumpsOff[k].x || on[k].y != clumpsOff[k].y || on[k].z != clumpsOff[k].z ||
                  on[k].w != clumpsOff[k].w;
    EXPECT_EQ(differ, 0u) << "clump poses that differ with " << variable;
    return on;
}

}  // namespace

// GPU only: integration and placement in one kernel (deme_integrate_and_place, the default for
// scenes without triangles) give the trajectory of the two kernels one after the other, bit for
// bit. A sphere placed before its owner's new pose was in place would drift from it.
TEST(CudaStepGraphs, FusedIntegrationAndPlacementEqualTwoKernelsBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    const std::vector<float4> fused = expectTheSameWhether("DEME_CUDA_FUSED_STEP");
    // The dumbbells fell and came to the plane (the comparison is of a run that did something).
    float lowest = 1.f;
    for (size_t k = 0; k < fused.size(); k += 2) lowest = std::min(lowest, fused[k].z);
    EXPECT_LT(lowest, -0.13f);
}

// Spheres of radius R and 2500 kg/m^3 of material `mat` at `pts`, added to `sim`, which is then
// initialised and run for `steps` steps under gravity: their tracker.
template <class Material>
std::shared_ptr<DEMTracker> spheresRunFor(DEMSolver& sim, const Material& mat, const std::vector<float3>& pts,
                                          int steps) {
    auto grains = sim.AddClumps(sim.LoadSphereType((float)sphereMass(R, 2500), R, mat), pts);
    sim.SetInitTimeStep(DT);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    auto t = sim.Track(grains);
    sim.DoDynamics(steps * DT);
    return t;
}

// 200 spheres resting far apart on a plane that rises at 5 cm/s and tilts at 0.2 rad/s about x (a
// prescribed external object, owner 200: past the first block of the step's owners), each with the
// plane as its one contact. Their positions and velocities after `steps` steps.
std::vector<float3> spheresOnATiltingLift(int steps) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.4, 0.01));
    sim.InstructBoxDomainDimension(1.0, 1.0, 1.0);
    auto lift = sim.AddExternalObject();
    lift->AddPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    lift->SetInitPos(make_float3(0, 0, -0.3f));
    lift->SetFamily(7);
    sim.SetFamilyPrescribedLinVel(7, "0", "0", "0.05");
    sim.SetFamilyPrescribedAngVel(7, "0.2", "0", "0");
    std::vector<float3> pts;
    for (int i = 0; i < 15 && pts.size() < 200; i++)
        for (int j = 0; j < 15 && pts.size() < 200; j++)
            pts.push_back(make_float3(-0.35f + 0.05f * i, -0.35f + 0.05f * j, -0.3f + R));
    auto t = spheresRunFor(sim, mat, pts, steps);
    std::vector<float3> out;
    for (size_t k = 0; k < pts.size(); k++) {
        out.push_back(t->Pos(k));
        out.push_back(t->Vel(k));
    }
    return out;
}

// The same samples (positions, velocities) bit for bit.
void expectSameSamples(const std::vector<float3>& a, const std::vector<float3>& b, const char* what) {
    ASSERT_EQ(a.size(), b.size());
    size_t differ = 0;
    for (size_t k = 0; k < a.size(); k++) differ += !same(a[k], b[k]);
    EXPECT_EQ(differ, 0u) << what << " that differ";
}

// GPU only: a moving analytical owner's components placed by the block of the fused step that stepped
// the owner (the default where one block did) give the trajectory of their placement by the block
// that finishes last, bit for bit. A wall placed before its owner's new pose was in place would lag
// a step behind, and the spheres on it with it.
TEST(CudaStepGraphs, AnalyticalOwnersPlacedByTheirBlockEqualTheLastBlockBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    std::vector<float3> last;
    {
        ScopedEnvironmentVariable v("DEME_CUDA_ANALYTICAL_IN_BLOCK", "0");
        last = spheresOnATiltingLift(5000);
    }
    ScopedEnvironmentVariable v("DEME_CUDA_ANALYTICAL_IN_BLOCK", "1");
    const std::vector<float3> own = spheresOnATiltingLift(5000);
    expectSameSamples(own, last, "sphere positions or velocities");
    // The lift carried them: 0.1 s at 5 cm/s is 5 mm up at x = 0 (the tilt about x leaves their
    // heights at y = 0 alone); the spheres at y = 0 have risen with it.
    for (size_t k = 0; k < own.size(); k += 2)
        if (std::fabs(own[k].y) < 1e-4f) EXPECT_NEAR(own[k].z, -0.3f + R + 0.005f, 5e-4f) << k / 2;
}

// 100 spheres falling freely from rest, far from each other and from every wall (no contacts at
// all): their heights after `steps` steps.
std::vector<float> freeFallHeights(int steps) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.4, 0.01));
    sim.InstructBoxDomainDimension(1.0, 1.0, 1.0);
    std::vector<float3> pts;
    for (int i = 0; i < 10; i++)
        for (int j = 0; j < 10; j++) pts.push_back(make_float3(-0.45f + 0.1f * i, -0.45f + 0.1f * j, 0.4f));
    auto t = spheresRunFor(sim, mat, pts, steps);
    std::vector<float> z;
    for (size_t k = 0; k < pts.size(); k++) z.push_back(t->Pos(k).z);
    return z;
}

// GPU only: the force pass of a scene without meshes, whose per-contact step leaves the triangle
// branch out (the default there), gives the trajectories of the pass of every type, bit for bit:
// the bouncing spheres, dumbbells landing on a plane, spheres on a moving plane.
TEST(CudaStepGraphs, NoMeshForcePassEqualsThePassOfEveryTypeBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    expectTheSameWhether("DEME_CUDA_NO_MESH_PASS");
    std::vector<float3> every;
    {
        ScopedEnvironmentVariable v("DEME_CUDA_NO_MESH_PASS", "0");
        every = spheresOnATiltingLift(5000);
    }
    ScopedEnvironmentVariable v("DEME_CUDA_NO_MESH_PASS", "1");
    expectSameSamples(spheresOnATiltingLift(5000), every, "sphere positions or velocities on the lift");
}

// GPU only: an owner step that reads its inputs before waiting for the force pass before it (the
// default) gives the trajectories of one that reads everything after, bit for bit: the bouncing
// spheres (prescribed motion, tracker loads, batches ended early), dumbbells landing on a plane,
// spheres on a moving plane. An input read before the step that wrote it had ended would make the
// runs differ. Where a step has no contacts, and so no force pass, the kernel before may be the last
// step's integration, and nothing may be read early: spheres in free fall, against the exact fall.
TEST(CudaStepGraphs, OwnerInputsReadBeforeTheForcePassEndsEqualReadAfterBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    expectTheSameWhether("DEME_CUDA_INPUTS_BEFORE_WAIT");
    std::vector<float3> after;
    std::vector<float> fallAfter;
    {
        ScopedEnvironmentVariable v("DEME_CUDA_INPUTS_BEFORE_WAIT", "0");
        after = spheresOnATiltingLift(5000);
        fallAfter = freeFallHeights(4000);
    }
    ScopedEnvironmentVariable v("DEME_CUDA_INPUTS_BEFORE_WAIT", "1");
    expectSameSamples(spheresOnATiltingLift(5000), after, "sphere positions or velocities on the lift");
    const std::vector<float> fall = freeFallHeights(4000);
    ASSERT_EQ(fall.size(), fallAfter.size());
    // 4000 steps of h = 2e-5 s: velocity first, then position, so after n steps the fall is exactly
    // g h^2 n (n + 1) / 2 (31.4 mm); float heights near 0.37 m resolve 3e-8 m.
    const double h = DT, n = 4000, exact = 0.4 - 0.5 * 9.81 * h * h * n * (n + 1);
    for (size_t k = 0; k < fall.size(); k++) {
        EXPECT_EQ(fall[k], fallAfter[k]) << k;
        EXPECT_NEAR(fall[k], exact, 1e-6) << k;
    }
}

// GPU only: a step's loads cleared by the integration before it (the default under 2^18 owners)
// give the trajectory of a kernel that clears them at every step's start, bit for bit. A load left
// from the step before would push them apart.
TEST(CudaStepGraphs, LoadsClearedByIntegrationEqualAClearingKernelBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    expectTheSameWhether("DEME_CUDA_LOADS_CLEARED_BY_INTEGRATION");
}

// GPU only: detection spread over several threads a sphere (the default below 2^18 spheres,
// backend/cuda/DetectionLanes.h: registration and pair search in lanes of bin rows) gives the
// trajectories of a thread an item, bit for bit: the same contact sets (here every sphere's and
// dumbbell's floor contacts, which a sphere's first lane finds), so the same steps. The kernels'
// lists of sphere pairs, lanes and wide spheres included, are held to the CPU's detector pair for
// pair on the host (CudaDetectionKernels.*).
TEST(CudaStepGraphs, DetectionInLanesEqualsAThreadAnItemBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    Trajectory one;
    std::vector<float4> dumbbellsOne;
    {
        ScopedEnvironmentVariable binning("DEME_CUDA_BINNING_LANES", "1"), search("DEME_CUDA_SEARCH_LANES", "1"),
            wide("DEME_CUDA_WIDE_SPHERES", "0");
        one = inOneCall(false);
        dumbbellsOne = fallingDumbbellPoses(6000);
    }
    ScopedEnvironmentVariable search("DEME_CUDA_SEARCH_LANES", "3");  // more than one lane whatever the rows
    expectBitForBit(inOneCall(false), one);
    const std::vector<float4> dumbbells = fallingDumbbellPoses(6000);
    ASSERT_EQ(dumbbells.size(), dumbbellsOne.size());
    for (size_t k = 0; k < dumbbells.size(); k++) {
        EXPECT_EQ(dumbbells[k].x, dumbbellsOne[k].x) << k;
        EXPECT_EQ(dumbbells[k].z, dumbbellsOne[k].z) << k;
        EXPECT_EQ(dumbbells[k].w, dumbbellsOne[k].w) << k;
    }
}

// GPU only: graphs of several steps (the default 8, and 7, whose batches of up to 30 steps leave
// remainders, with batches ended early inside a graph) equal graphs of one step, bit for bit.
TEST(CudaStepGraphs, GraphsOfSeveralStepsEqualOneStepGraphsBitForBit) {
    if (!cuda::cudaBackendBuilt() || cuda::usableDevices().empty()) GTEST_SKIP() << "needs a GPU";
    ScopedEnvironmentVariable backend("DEME_BACKEND", "cuda");
    Trajectory one;
    {
        ScopedEnvironmentVariable steps("DEME_CUDA_GRAPH_STEPS", "1");
        one = inOneCall(false);
    }
    for (const char* n : {"8", "7"}) {
        SCOPED_TRACE(std::string("steps per graph ") + n);
        ScopedEnvironmentVariable steps("DEME_CUDA_GRAPH_STEPS", n);
        expectBitForBit(inOneCall(false), one);
    }
}

// The number of steps per graph is read from the environment; anything but a whole number from 1 to
// 256 is an error that names the variable and the value (checked without a GPU).
TEST(CudaStepGraphs, StepsPerGraphComesFromTheEnvironment) {
    {
        ScopedEnvironmentVariable unset("DEME_CUDA_GRAPH_STEPS", "");
        EXPECT_EQ(cuda::stepsPerGraph(), 8u);
    }
    {
        ScopedEnvironmentVariable one("DEME_CUDA_GRAPH_STEPS", "1");
        EXPECT_EQ(cuda::stepsPerGraph(), 1u);
    }
    for (const char* bad : {"0", "257", "8x", "-1"}) {
        ScopedEnvironmentVariable v("DEME_CUDA_GRAPH_STEPS", bad);
        try {
            cuda::stepsPerGraph();
            ADD_FAILURE() << "no error for " << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("DEME_CUDA_GRAPH_STEPS is '") + bad + "'"),
                      std::string::npos)
                << e.what();
        }
    }
}
