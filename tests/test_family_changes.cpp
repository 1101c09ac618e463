// Family changes of single owners: conditions (ChangeFamilyWhen, checked at each contact detection)
// and the tracker's SetFamily / SetFamilies, against the free-flight answer x(t) = x0 + v t.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "BackendFixture.h"
#include "BadInputChecks.h"
#include "TestHelpers.h"
#include "ScratchDirTest.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "codegen/Expression.h"
#include "codegen/FamilyCondition.h"
#include "codegen/FamilyConditionSource.h"
#include "jit/KernelCache.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(FamilyChanges);

namespace {

// 40 spheres in a row along y, 5 cm apart (no contacts, no gravity), at x0 = -0.5 m, moving in +x
// at v_i = 0.05 i + 0.013 m/s: after T = 0.5 s sphere i is at -0.5 + v_i T, past the plane x = 0 for
// i >= 20 and short of it for i < 20 (the nearest ones are 6.7 mm and 18 mm from it).
constexpr int N = 40;
constexpr double T = 0.5, DT = 1e-4;
constexpr unsigned int CD_FREQ = 20;  // a detection (and a check) at least every 20 steps
float speedOf(int i) { return 0.05f * (float)i + 0.013f; }

struct Row {
    DEMSolver sim;
    std::shared_ptr<DEMClumpBatch> batch;
    std::shared_ptr<DEMTracker> tr;
    explicit Row(bool sync = true) {
        sim.SetVerbosity("QUIET");
        auto mat = sim.LoadMaterial(material(1e8, 0.3, 0.5, 0.5));
        sim.InstructBoxDomainDimension(4, 4, 4);
        auto tmpl = sim.LoadSphereType((float)sphereMass(0.01, 1000), 0.01f, mat);
        std::vector<float3> pts;
        std::vector<float3> vel;
        for (int i = 0; i < N; i++) {
            pts.push_back(make_float3(-0.5f, -1.0f + 0.05f * (float)i, 0.f));
            vel.push_back(make_float3(speedOf(i), 0.f, 0.f));
        }
        batch = sim.AddClumps(tmpl, pts);
        batch->SetVel(vel);
        sim.SetFamilyFixed(1);
        sim.SetInitTimeStep(DT);
        sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
        sim.SetSynchronousContactDetection(sync);
        sim.DisableAdaptiveUpdateFreq();
        sim.SetCDUpdateFreq(CD_FREQ);
    }
};

}  // namespace

// The test: every grain that crosses the plane x = 0 is frozen (family 1 is fixed) just past
// it, and no other grain is touched. A grain is checked at each detection, so it is frozen at most
// one detection interval (CD_FREQ steps) after it crossed: 0 < x <= v * CD_FREQ * dt.
// With asynchronous detection the check runs when an order is sent, at most CD_FREQ steps apart too.
static void freezeAtPlane(bool sync) {
    Row row(sync);
    row.sim.ChangeFamilyWhen(0, 1, "X > 0");
    row.sim.Initialize();
    row.tr = row.sim.Track(row.batch);
    row.sim.DoDynamics(T);
    const double t = row.sim.GetSimTime();
    int frozen = 0;
    const std::vector<unsigned int> fams = row.tr->GetFamilies();
    for (int i = 0; i < N; i++) {
        const float3 p = row.tr->Pos(i), v = row.tr->Vel(i);
        const double free = -0.5 + (double)speedOf(i) * t;  // where free flight puts it
        EXPECT_NEAR(p.y, -1.0f + 0.05f * (float)i, 1e-6);
        EXPECT_NEAR(p.z, 0.f, 1e-9);
        EXPECT_EQ(row.tr->GetFamily(i), fams[i]);
        if (free > 0.0) {
            frozen++;
            EXPECT_EQ(fams[i], 1u) << "grain " << i << " crossed the plane but was not frozen";
            EXPECT_EQ(v.x, 0.f) << "grain " << i;
            EXPECT_GT(p.x, 0.f) << "grain " << i << " frozen before it crossed";
            EXPECT_LE(p.x, speedOf(i) * CD_FREQ * DT * (1 + 1e-3) + 1e-6) << "grain " << i << " frozen late";
        } else {
            EXPECT_EQ(fams[i], 0u) << "grain " << i << " never crossed but was frozen";
            EXPECT_NEAR(p.x, free, 1e-5) << "grain " << i;  // free flight, untouched
            EXPECT_FLOAT_EQ(v.x, speedOf(i));
        }
    }
    EXPECT_EQ(frozen, N / 2);
}

DEME_BACKEND_TEST(FamilyChanges, ChangeFamilyWhenFreezesEveryGrainThatCrossesAPlane) { freezeAtPlane(true); }
DEME_BACKEND_TEST(FamilyChanges, ChangeFamilyWhenFreezesAtPlaneWithAsynchronousDetection) { freezeAtPlane(false); }

// A condition of time and velocity, with || and !: all grains faster than 1 m/s change family once
// t > 0.1 s; the others keep theirs; a second call goes on checking.
DEME_BACKEND_TEST(FamilyChanges, ConditionsReadTimeAndVelocity) {
    Row row;
    row.sim.ChangeFamilyWhen(0, 2, "t > 0.1 && !(Vx <= 1) || Y > 100");
    row.sim.Initialize();
    row.tr = row.sim.Track(row.batch);
    row.sim.DoDynamics(0.05);
    for (int i = 0; i < N; i++) EXPECT_EQ(row.tr->GetFamily(i), 0u) << "grain " << i;
    row.sim.DoDynamics(0.1);
    for (int i = 0; i < N; i++) EXPECT_EQ(row.tr->GetFamily(i), speedOf(i) > 1.f ? 2u : 0u) << "grain " << i;
}

// ClearFamilyChangeConditions ends every condition between calls: the grains the condition caught
// before stay frozen, and those that cross the plane afterwards fly on (x = x0 + v t, 1e-5 m).
DEME_BACKEND_TEST(FamilyChanges, ClearedConditionsCatchNoMoreGrains) {
    Row row;
    row.sim.ChangeFamilyWhen(0, 1, "X > 0");
    row.sim.Initialize();
    row.tr = row.sim.Track(row.batch);
    row.sim.DoDynamics(0.4);  // past the plane by then: v > 1.25 m/s, grains 25..39
    const std::vector<unsigned int> caught = row.tr->GetFamilies();
    int before = 0;
    for (unsigned int f : caught) before += f == 1u;
    ASSERT_GT(before, 0);
    row.sim.ClearFamilyChangeConditions();
    row.sim.DoDynamics(T - 0.4);  // grains 20..24 cross now
    const double t = row.sim.GetSimTime();
    int crossedAfter = 0;
    for (int i = 0; i < N; i++) {
        EXPECT_EQ(row.tr->GetFamily(i), caught[i]) << "grain " << i;
        if (caught[i] == 0u) {
            const double free = -0.5 + (double)speedOf(i) * t;
            EXPECT_NEAR(row.tr->Pos(i).x, free, 1e-5) << "grain " << i;
            crossedAfter += free > 0.0;
        }
    }
    EXPECT_GT(crossedAfter, 0);  // some did cross the plane after the conditions went
}

// SetFamily freezes one grain between calls; SetFamilies sets them all, and the grains it puts back
// in family 0 move on from where they stopped.
DEME_BACKEND_TEST(FamilyChanges, TrackerSetFamilyFreezesOneGrainOnly) {
    Row row;
    row.sim.Initialize();
    row.tr = row.sim.Track(row.batch);
    row.sim.DoDynamics(0.1);
    row.tr->SetFamily(1, 7);
    const float3 stopped = row.tr->Pos(7);
    row.sim.DoDynamics(0.1);
    const double t = row.sim.GetSimTime();
    for (int i = 0; i < N; i++) {
        const float3 p = row.tr->Pos(i);
        if (i == 7) {
            EXPECT_EQ(p.x, stopped.x);
            EXPECT_EQ(row.tr->GetFamily(i), 1u);
        } else {
            EXPECT_NEAR(p.x, -0.5 + (double)speedOf(i) * t, 1e-5) << "grain " << i;
            EXPECT_EQ(row.tr->GetFamily(i), 0u);
        }
    }
    // Family 1 is fixed: velocity 0 stays 0 when the grain is released.
    row.tr->SetFamilies(std::vector<unsigned int>(N, 0u));
    row.sim.DoDynamics(0.1);
    EXPECT_EQ(row.tr->Pos(7).x, stopped.x);
    EXPECT_EQ(row.tr->GetFamily(7), 0u);
}

TEST(FamilyChangesInput, BadCallsAreErrorsThatChangeNothing) {
    Row row;
    EXPECT_THROW(row.sim.ChangeFamilyWhen(0, 256, "X > 0"), deme::Error);
    expectDemeError([&] { row.sim.ChangeFamilyWhen(0, 1, "Q > 0"); }, {"ChangeFamilyWhen", "unknown", "'Q'"});
    expectDemeError([&] { row.sim.ChangeFamilyWhen(0, 1, "X > "); }, {"ChangeFamilyWhen", "position 5"});
    expectDemeError([&] { row.sim.ChangeFamilyWhen(0, 1, "X = 0"); }, {"ChangeFamilyWhen"});
    row.sim.Initialize();
    row.tr = row.sim.Track(row.batch);
    expectDemeError([&] { row.tr->SetFamily(300, 0); }, {"SetFamily", "300"});
    std::vector<unsigned int> fams(N, 1u);
    fams[N - 1] = 999;
    expectDemeError([&] { row.tr->SetFamilies(fams); }, {"SetFamilies", "999"});
    for (int i = 0; i < N; i++) EXPECT_EQ(row.tr->GetFamily(i), 0u);  // nothing applied
    expectDemeError([&] { row.tr->SetFamilies(std::vector<unsigned int>(3, 0u)); }, {"SetFamilies", "3"});
    row.sim.DoDynamics(0.01);  // no condition was stored by the failed calls
    for (int i = 0; i < N; i++) EXPECT_EQ(row.tr->GetFamily(i), 0u);
}

TEST(ExpressionCondition, ComparisonsAndLogicEvaluateToOneOrZero) {
    const std::vector<std::string>& vars = familyConditionVariables();
    auto eval = [&](const std::string& text, std::vector<double> v) {
        v.resize(vars.size(), 0.0);
        return Expression::parseCondition(text, vars, "test").evaluate(v.data());
    };
    EXPECT_EQ(eval("X > 1", {2}), 1.0);
    EXPECT_EQ(eval("X > 1", {1}), 0.0);
    EXPECT_EQ(eval("X >= 1", {1}), 1.0);
    EXPECT_EQ(eval("X <= 1 && Y < 0", {1, -1}), 1.0);
    EXPECT_EQ(eval("X == 1 || Y != 2", {0, 2}), 0.0);
    EXPECT_EQ(eval("!(X < 0) && (Y + 1) * 2 > 3", {0, 1}), 1.0);
    EXPECT_EQ(eval("X < 1 || Y < 1 && Z < 1", {0, 5, 5}), 1.0);  // && binds tighter than ||
    EXPECT_EQ(eval("abs(X - 0.5 * t) < 0.2", {1.0, 0, 0, 0, 0, 0, 1.7}), 1.0);
    EXPECT_EQ(eval("X", {3}), 3.0);  // a value is a condition that holds where it is not 0
    // Values (prescribed motions) still refuse comparisons.
    EXPECT_THROW(Expression::parse("t > 1", {"t"}, "test"), deme::Error);
    // The generated C++ computes the same 1.0 / 0.0 (the GPU kernel's text).
    const std::string src = Expression::parseCondition("X < 1 && !(Y > 2)", vars, "test").toCppSource(
        {"x", "y", "z", "vx", "vy", "vz", "t"});
    EXPECT_NE(src.find("((x) < (0x1p+0))"), std::string::npos) << src;
    EXPECT_NE(src.find("&&"), std::string::npos) << src;
}

// The GPU's condition kernel as generated source: comparisons, logic and functions of all seven
// variables compile for sm_90 to PTX (no GPU needed; skipped in a library built without CUDA).
class FamilyConditionNvrtc : public deme_test::ScratchDirTest {
  protected:
    void SetUp() override {
        if (!cuda::cudaBackendBuilt()) GTEST_SKIP() << "the library was built without the CUDA backend";
        ScratchDirTest::SetUp();
    }
};

TEST_F(FamilyConditionNvrtc, ConditionKernelCompilesToPtx) {
    std::vector<FamilyCondition> rules(3);
    const char* const texts[] = {"X > 0 && !(Y <= 1) || Z == 2", "abs(X - (0.06 + 0.2 * t)) < 0.06 && Vz < 0",
                                 "sqrt(Vx*Vx + Vy*Vy) >= max(0.1, t) || min(X, Y) != 0"};
    for (int i = 0; i < 3; i++) {
        rules[i].from = (family_t)i;
        rules[i].to = (family_t)(i + 1);
        rules[i].when = Expression::parseCondition(texts[i], familyConditionVariables(), "test");
    }
    const std::string source = familyConditionKernelSource(rules);
    EXPECT_NE(source.find(kFamilyConditionKernel), std::string::npos);
    jit::KernelCache cache(dir.string());
    cuda::CudaCompileOptions options;
    options.architecture = "compute_90";
    try {
        const cuda::CudaCompileResult r =
            cuda::compileCudaSource("test", "deme_family_conditions.cu", source, options, cache);
        EXPECT_NE(r.image.find(kFamilyConditionKernel), std::string::npos);
    } catch (const deme::Error& e) {
        ADD_FAILURE() << e.what() << "\n" << source;
    }
}
