// Custom force models with owner and contact wildcards (docs/force-models.md): an electrostatic model
// acting at a distance follows Coulomb's law, owner wildcards set from the host change its force, and
// a contact wildcard counts a contact's age across re-detections and restarts for a new contact.
#include <gtest/gtest.h>

#include <cmath>

#include "BackendFixture.h"
#include "ForceModelTestUtil.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(ForceModelWildcards);
DEME_BACKEND_TEST_SUITE(ForceModelContactWildcards);

namespace {

constexpr double kCoulomb = 8.9875517923e9;  // N m^2 / C^2

// Two charged spheres on the x axis, held in place (fixed family), with an extra margin of 0.1 m so
// that the pair is in the contact set while their surfaces are less than 0.2 m apart.
struct ChargedPair {
    DEMSolver sim;
    std::shared_ptr<DEMTracker> spheres;
    static constexpr float r = 0.005f;
    // backend: "" for the one the solver takes by default (a backend test's instance).
    explicit ChargedPair(const std::string& backend = "") {
        sim.SetVerbosity("QUIET");
        if (!backend.empty()) sim.SetBackend(backend);
        auto mat = sim.LoadMaterial({});
        sim.DefineContactForceModel(kElectrostatic)->SetPerOwnerWildcards({"Q"});
        sim.InstructBoxDomainDimension(1, 1, 1);
        auto tmpl = sim.LoadSphereType(1e-3f, r, mat);
        auto batch = sim.AddClumps(tmpl, {make_float3(-0.01f, 0, 0), make_float3(0.01f, 0, 0)});
        sim.SetFamilyFixed(0);
        sim.SetFamilyExtraMargin(0, 0.1f);
        sim.SetInitTimeStep(1e-5);
        sim.Initialize();
        spheres = sim.Track(batch);
    }
    // The x force on sphere 1 (sphere 0 gets the opposite) with the spheres `s` apart, after a step.
    double forceAt(double s) {
        spheres->SetPos(make_float3((float)(-0.5 * s), 0, 0), 0);
        spheres->SetPos(make_float3((float)(0.5 * s), 0, 0), 1);
        sim.DoStepDynamics();
        const float3 f0 = spheres->ContactForce(0), f1 = spheres->ContactForce(1);
        EXPECT_EQ(f0.x, -f1.x);  // the engine applies the reaction to B
        EXPECT_EQ(f1.y, 0.f);
        EXPECT_EQ(f1.z, 0.f);
        return f1.x;
    }
};

}  // namespace

// Test 2 of the issue: F = k Q1 Q2 / s^2 within 1 % (the bound) from 3 to 40 radii apart. The
// model computes in double from float positions, so the error is expected near float resolution.
// On the GPU: the generated kernel, which also computes in double from the same float positions.
DEME_BACKEND_TEST(ForceModelWildcards, ElectrostaticForceFollowsCoulombsLaw) {
    ChargedPair p;
    const float Q0 = 1e-6f, Q1 = 2e-6f;
    p.sim.SetOwnerWildcardValue("Q", 0, Q0);
    p.sim.SetOwnerWildcardValue("Q", 1, Q1);
    double worst = 0.0;
    for (double s : {0.015, 0.02, 0.03, 0.05, 0.08, 0.12, 0.2}) {
        // Where the spheres are after SetPos (float positions), as the engine sees them.
        const double x0 = (double)(float)(-0.5 * s), x1 = (double)(float)(0.5 * s);
        const double expected = kCoulomb * (double)Q0 * (double)Q1 / ((x1 - x0) * (x1 - x0));
        const double got = p.forceAt(s);
        const double rel = std::fabs(got - expected) / expected;
        EXPECT_LT(rel, 0.01) << "separation " << s << ": " << got << " N, Coulomb " << expected << " N";
        worst = std::max(worst, rel);
    }
    std::cout << "[ coulomb  ] largest relative error " << worst << std::endl;
    // Beyond the reach of the margin the pair leaves the contact set: no force.
    EXPECT_EQ(p.forceAt(0.35), 0.0);
}

namespace {

// Test 4 of the issue: owner wildcards set between DoDynamics calls, singly, as a range, per family
// or through a tracker, change the force as the model says (exact ratios of float products). On the
// GPU: owner wildcards set on the host reach the GPU's model.
void checkOwnerWildcardsChangeTheForce() {
    ChargedPair p;
    const double s = 0.03;
    p.sim.SetOwnerWildcardValue("Q", 0, std::vector<float>{1e-6f, 1e-6f});
    const double f1 = p.forceAt(s);
    EXPECT_GT(f1, 0.0);  // like charges repel
    EXPECT_FLOAT_EQ(p.sim.GetOwnerWildcardValue("Q", 1), 1e-6f);

    p.sim.SetOwnerWildcardValue("Q", 1, -3e-6f);  // unlike charges attract, three times as hard
    EXPECT_NEAR(p.forceAt(s) / f1, -3.0, 1e-6);

    p.spheres->SetOwnerWildcardValue("Q", 2e-6f, 0);
    EXPECT_FLOAT_EQ(p.spheres->GetOwnerWildcardValue("Q", 0), 2e-6f);
    EXPECT_NEAR(p.forceAt(s) / f1, -6.0, 1e-6);

    p.sim.SetFamilyOwnerWildcardValue(0, "Q", 0.5e-6f);  // both spheres are in family 0
    EXPECT_NEAR(p.forceAt(s) / f1, 0.25, 1e-6);
    const std::vector<float> both = p.sim.GetOwnerWildcardValue("Q", 0, 2);
    EXPECT_EQ(both, (std::vector<float>{0.5e-6f, 0.5e-6f}));

    p.sim.SetOwnerWildcardValue("Q", 0, 0.f);
    EXPECT_EQ(p.forceAt(s), 0.0);
}

}  // namespace

DEME_BACKEND_TEST(ForceModelWildcards, OwnerWildcardChangesTheForce) { checkOwnerWildcardsChangeTheForce(); }

// A family value given before Initialize is applied by it.
DEME_BACKEND_TEST(ForceModelWildcards, FamilyOwnerValueBeforeInitialize) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial({});
    sim.DefineContactForceModel(kElectrostatic)->SetPerOwnerWildcards({"Q"});
    sim.InstructBoxDomainDimension(1, 1, 1);
    auto tmpl = sim.LoadSphereType(1e-3f, 0.005f, mat);
    auto a = sim.AddClumps(tmpl, {make_float3(-0.1f, 0, 0)});
    auto b = sim.AddClumps(tmpl, {make_float3(0.1f, 0, 0)});
    b->SetFamily(3);
    sim.SetFamilyOwnerWildcardValue(3, "Q", 7e-7f);
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    EXPECT_EQ(sim.GetOwnerWildcardValue("Q", 0), 0.f);
    EXPECT_EQ(sim.GetOwnerWildcardValue("Q", 1), 7e-7f);
}

namespace {

// Sphere 0 flies at 1 m/s along x through sphere 1, which is fixed (the model gives no force), turns
// round far away and comes back through it: two contacts of the same pair, each about 200 steps long.
// On the GPU the owner wildcard the model writes there is read back on the host every step.
// editEveryStep: a third sphere, far from both, has its velocity set by a tracker before every step,
// an edit of the owners that sends them to the backend and re-detects: the pair's history stays
// (on a GPU the contact set never leaves the device for it).
void checkContactAge(bool async, float initialAge, bool editEveryStep = false) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial({});
    auto model = sim.DefineContactForceModel(kAgeCounter);
    model->SetPerContactWildcards({"age"});
    model->SetPerOwnerWildcards({"ageSeen"});
    sim.InstructBoxDomainDimension(1, 1, 1);
    const float r = 0.01f;
    auto tmpl = sim.LoadSphereType(1e-3f, r, mat);
    // Positions x0 + n h v never come within 5e-5 m of touching (|x| = 2r), far above float rounding.
    auto mover = sim.AddClumps(tmpl, {make_float3(-0.03005f, 0, 0)});
    auto target = sim.AddClumps(tmpl, {make_float3(0, 0, 0)});
    target->SetFamily(1);
    sim.SetFamilyFixed(1);
    mover->SetVel(std::vector<float3>{make_float3(1, 0, 0)});
    auto bystander = sim.AddClumps(tmpl, {make_float3(0.3f, 0.3f, 0.3f)});
    if (initialAge != 0.f) sim.SetFamilyContactWildcardInitValue(0, 1, "age", initialAge);
    sim.SetInitTimeStep(1e-4);
    // Re-detection every 3 steps at most: the count must survive some 130 of them per contact.
    sim.SetCDUpdateFreq(3);
    sim.DisableAdaptiveUpdateFreq();
    sim.SetSynchronousContactDetection(!async);
    sim.Initialize();
    auto tr = sim.Track(mover);
    auto still = sim.Track(bystander);
    for (int pass = 0; pass < 2; pass++) {
        // The pair has left the contact set (0.04 m apart, far beyond the margin): a new contact.
        double expected = initialAge;
        int contactSteps = 0;
        for (int step = 0; step < 900; step++) {
            // The force pass of this step sees the positions from before it.
            if (std::fabs(tr->Pos().x) < 2 * r) {
                expected += 1;
                contactSteps++;
            }
            if (editEveryStep) still->SetVel(make_float3(0, 0, 0));
            sim.DoStepDynamics();
            if (contactSteps > 0)
                ASSERT_EQ(sim.GetOwnerWildcardValue("ageSeen", 0), expected) << "pass " << pass << ", step " << step;
        }
        EXPECT_EQ(contactSteps, 400);
        tr->SetVel(make_float3(pass == 0 ? -1.f : 1.f, 0, 0));
    }
}

}  // namespace

// Test 5 of the issue, with every-step comparison in both detection modes.
DEME_BACKEND_TEST(ForceModelContactWildcards, CounterEqualsContactAgeAcrossRedetection) { checkContactAge(false, 0.f); }
DEME_BACKEND_TEST(ForceModelContactWildcards, CounterEqualsContactAgeAsync) { checkContactAge(true, 0.f); }
// A contact between families 0 and 1 starts at the value set for them.
DEME_BACKEND_TEST(ForceModelContactWildcards, FamilyInitialValue) { checkContactAge(false, 1000.f); }
DEME_BACKEND_TEST(ForceModelContactWildcards, CounterSurvivesTrackerEditsEveryStep) {
    checkContactAge(false, 0.f, true);
}

// The generated GPU kernel and the CPU's code give the same Coulomb force to 1e-5 (both compute in
// double from the same float positions); each against the law: ElectrostaticForceFollowsCoulombsLaw.
TEST(GpuParity, CustomModelCoulombForce) {
    if (!gpuPresent()) GTEST_SKIP() << "no usable GPU";
    ChargedPair cpu("cpu"), gpu("cuda");
    ASSERT_EQ(gpu.sim.GetBackend(), "cuda");
    for (ChargedPair* p : {&cpu, &gpu}) {
        p->sim.SetOwnerWildcardValue("Q", 0, 1e-6f);
        p->sim.SetOwnerWildcardValue("Q", 1, 2e-6f);
    }
    for (double s : {0.015, 0.03, 0.08, 0.2}) {
        const double fc = cpu.forceAt(s), fg = gpu.forceAt(s);
        EXPECT_NEAR(fg, fc, 1e-5 * std::fabs(fc)) << "separation " << s;
    }
}
