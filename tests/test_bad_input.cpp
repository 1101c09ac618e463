// Bad input must be rejected with deme::Error (never a crash, never silently accepted), and each
// message must name the API call that failed (include/deme/Error.h: "<call>: <message>"; input from
// files also names "<file>:<line>:"). Expected call names come from src/api/*.cpp and src/io/.
#include <deme/deme.h>
#include <gtest/gtest.h>

#include "BadInputChecks.h"
#include "ScratchDirTest.h"
#include "backend/cuda/Device.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

using namespace deme;
using namespace deme_test;
namespace fs = std::filesystem;

namespace {

class BadInputFiles : public deme_test::ScratchDirTest {
  protected:
};

}  // namespace

// The reference scene itself is valid: guards every test below against failing for the wrong reason.
TEST(BadInput, MinimalSceneIsValid) {
    Scene1 s;
    EXPECT_NO_THROW(s.sim.Initialize());
    EXPECT_NO_THROW(s.sim.DoDynamics(1e-4));
    EXPECT_EQ(s.sim.GetNumClumps(), 1u);
}

// ---------------------------------------------------------------- templates

TEST(BadInput, LoadSphereTypeNonPositiveRadius) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    EXPECT_DEME_ERROR([&] { sim.LoadSphereType(1.f, -0.01f, mat); }, {"LoadSphereType", "radius"});
    EXPECT_DEME_ERROR([&] { sim.LoadSphereType(1.f, 0.f, mat); }, {"LoadSphereType", "radius"});
    EXPECT_DEME_ERROR([&] { sim.LoadSphereType(1.f, std::numeric_limits<float>::quiet_NaN(), mat); },
                      {"LoadSphereType", "radius"});
}

TEST(BadInput, LoadSphereTypeNonPositiveMass) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    EXPECT_DEME_ERROR([&] { sim.LoadSphereType(-1.f, 0.01f, mat); }, {"LoadSphereType", "mass"});
    EXPECT_DEME_ERROR([&] { sim.LoadSphereType(0.f, 0.01f, mat); }, {"LoadSphereType", "mass"});
}

TEST(BadInput, LoadClumpTypeNonPositiveRadius) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    const float3 moi = make_float3(1e-4f);
    const std::vector<float3> pos = {make_float3(-0.01f, 0, 0), make_float3(0.01f, 0, 0)};
    EXPECT_DEME_ERROR(
        [&] {
            sim.LoadClumpType(1.f, moi, std::vector<float>{0.01f, -0.01f}, pos, mat);
        },
        {"LoadClumpType", "radius"});
    EXPECT_DEME_ERROR(
        [&] {
            sim.LoadClumpType(1.f, moi, std::vector<float>{0.f, 0.01f}, pos, mat);
        },
        {"LoadClumpType", "radius"});
    // No spheres at all is also rejected.
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(1.f, moi, std::vector<float>{}, std::vector<float3>{}, mat); },
                      {"LoadClumpType"});
}

TEST(BadInput, LoadClumpTypeNonPositiveMass) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    const std::vector<float> r = {0.01f};
    const std::vector<float3> p = {make_float3(0.f)};
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(0.f, make_float3(1e-4f), r, p, mat); }, {"LoadClumpType", "mass"});
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(-2.f, make_float3(1e-4f), r, p, mat); }, {"LoadClumpType", "mass"});
}

TEST(BadInput, LoadClumpTypeNonPositiveMOI) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    const std::vector<float> r = {0.01f};
    const std::vector<float3> p = {make_float3(0.f)};
    // Each principal moment separately: zero, negative, zero.
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(1.f, make_float3(0.f, 1e-4f, 1e-4f), r, p, mat); },
                      {"LoadClumpType", "MOI"});
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(1.f, make_float3(1e-4f, -1e-4f, 1e-4f), r, p, mat); },
                      {"LoadClumpType", "MOI"});
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(1.f, make_float3(1e-4f, 1e-4f, 0.f), r, p, mat); },
                      {"LoadClumpType", "MOI"});
}

TEST(BadInput, LoadClumpTypeMismatchedSizes) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    // 2 radii, 1 position.
    EXPECT_DEME_ERROR(
        [&] {
            sim.LoadClumpType(1.f, make_float3(1e-4f), std::vector<float>{0.01f, 0.01f},
                              std::vector<float3>{make_float3(0.f)}, mat);
        },
        {"LoadClumpType", "2 radii", "1 positions"});
    // 1 radius, 1 position, 2 materials.
    EXPECT_DEME_ERROR(
        [&] {
            sim.LoadClumpType(1.f, make_float3(1e-4f), std::vector<float>{0.01f}, std::vector<float3>{make_float3(0.f)},
                              std::vector<std::shared_ptr<DEMMaterial>>{mat, mat});
        },
        {"LoadClumpType", "2 materials"});
    // A null material.
    EXPECT_DEME_ERROR(
        [&] {
            sim.LoadClumpType(1.f, make_float3(1e-4f), std::vector<float>{0.01f}, std::vector<float3>{make_float3(0.f)},
                              std::shared_ptr<DEMMaterial>());
        },
        {"LoadClumpType", "null"});
}

// ---------------------------------------------------------------- materials

// Property names must be C++ identifiers (force models read them by name). Which ones a model needs,
// and whether a built-in model knows them, is checked at Initialize.
TEST(BadInput, LoadMaterialUnknownProperty) {
    for (const char* bad : {"Young's", "2mu", "", "C o R"}) {
        DEMSolver sim;
        sim.SetVerbosity("QUIET");
        auto props = goodMaterial();
        props[bad] = 1.0;
        EXPECT_DEME_ERROR([&] { sim.LoadMaterial(props); }, {"LoadMaterial", "identifier"});
    }
    // The built-in model reads E, nu, CoR, mu, Crr only: another name is a typo for it.
    for (const char* typo : {"Young", "cor"}) {
        SCOPED_TRACE(typo);
        Scene1 s;
        auto props = goodMaterial();
        props[typo] = 0.5;
        s.sim.LoadMaterial(props);
        EXPECT_DEME_ERROR([&] { s.sim.Initialize(); }, {"Initialize", std::string("\"") + typo + "\""});
    }
}

TEST(BadInput, LoadMaterialMissingRequiredProperty) {
    for (const char* missing : {"E", "nu", "CoR", "mu"}) {
        SCOPED_TRACE(missing);
        Scene1 s;
        auto props = goodMaterial();
        props.erase(missing);
        s.sim.LoadMaterial(props);  // a custom model might not need it
        EXPECT_DEME_ERROR([&] { s.sim.Initialize(); },
                          {"Initialize", "material 1", std::string("no property \"") + missing + "\""});
    }
}

TEST(BadInput, LoadMaterialOutOfRange) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    // Ranges from src/api/DEMSolver.cpp: E > 0, 0 <= nu < 0.5, 0 <= CoR <= 1, mu >= 0.
    const std::vector<std::pair<std::string, double>> bad = {{"nu", 0.5},   {"nu", 0.7}, {"nu", -0.1}, {"CoR", 1.01},
                                                             {"CoR", -0.1}, {"E", 0.0},  {"E", -1e8},  {"mu", -0.2}};
    for (const auto& b : bad) {
        SCOPED_TRACE(b.first + " = " + std::to_string(b.second));
        auto props = goodMaterial();
        props[b.first] = b.second;
        EXPECT_DEME_ERROR([&] { sim.LoadMaterial(props); }, {"LoadMaterial", b.first});
    }
    auto props = goodMaterial();
    props["E"] = std::numeric_limits<double>::infinity();
    EXPECT_DEME_ERROR([&] { sim.LoadMaterial(props); }, {"LoadMaterial", "E"});
    // The boundary values that are allowed still load.
    props = goodMaterial();
    props["CoR"] = 1.0;
    props["nu"] = 0.0;
    EXPECT_NO_THROW(sim.LoadMaterial(props));
}

// ---------------------------------------------------------------- clump CSV files

TEST_F(BadInputFiles, MalformedCsvRowNamesFileAndLine) {
    // Line 1 header, line 2 a valid sphere, line 3 a non-numeric y field.
    const std::string path = write("bad.csv", "x,y,z,r\n0,0,0,0.01\n0.01,abc,0,0.01\n");
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(1.f, make_float3(1e-4f), path, mat); },
                      {"LoadClumpType", path + ":3:", "abc"});
}

TEST_F(BadInputFiles, NonPositiveRadiusInCsv) {
    const std::string path = write("neg.csv", "x,y,z,r\n0,0,0,0.01\n0.01,0,0,-0.01\n");
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(1.f, make_float3(1e-4f), path, mat); },
                      {"LoadClumpType", path + ":3:", "radius"});
}

TEST_F(BadInputFiles, MissingCsvFile) {
    // Unreadable file: line 0 (src/io/ClumpCsvReader.h).
    const std::string path = (dir / "does_not_exist.csv").string();
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    EXPECT_DEME_ERROR([&] { sim.LoadClumpType(1.f, make_float3(1e-4f), path, mat); }, {"LoadClumpType", path + ":0:"});
}

TEST_F(BadInputFiles, ValidCsvLoads) {
    // Guards the two tests above: the same layout with numeric fields is accepted.
    const std::string path = write("good.csv", "x,y,z,r\n0,0,0,0.01\n0.01,0.02,0,0.01\n");
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    std::shared_ptr<DEMClumpTemplate> t;
    ASSERT_NO_THROW(t = sim.LoadClumpType(1.f, make_float3(1e-4f), path, mat));
    EXPECT_EQ(t->GetNumSpheres(), 2u);
}

// ---------------------------------------------------------------- order of calls

TEST(BadInput, SceneBuildingCallsAfterInitialize) {
    Scene1 s;
    s.sim.Initialize();
    EXPECT_DEME_ERROR([&] { s.sim.LoadMaterial(goodMaterial()); }, {"LoadMaterial", "Initialize"});
    EXPECT_DEME_ERROR([&] { s.sim.Initialize(); }, {"Initialize", "before Initialize"});
    EXPECT_DEME_ERROR([&] { s.batch->SetVel(make_float3(1, 0, 0)); }, {"DEMClumpBatch::SetVel"});
    // Templates and clumps may be added during a run (docs/scene-changes.md): a batch waits for
    // UpdateClumps, and a clump outside the domain is refused at once.
    auto tmpl = s.sim.LoadSphereType(1.f, 0.01f, s.mat);
    s.sim.AddClumps(tmpl, {make_float3(0.1f, 0, 0)});
    EXPECT_DEME_ERROR([&] { s.sim.AddClumps(tmpl, {make_float3(1e3f, 0, 0)}); }, {"AddClumps", "outside"});
    EXPECT_EQ(s.sim.GetNumClumps(), 1u);
    s.sim.UpdateClumps();
    EXPECT_EQ(s.sim.GetNumClumps(), 2u);
}

TEST(BadInput, SetInitTimeStepNonPositive) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    EXPECT_DEME_ERROR([&] { sim.SetInitTimeStep(0.0); }, {"SetInitTimeStep"});
    EXPECT_DEME_ERROR([&] { sim.SetInitTimeStep(-1e-5); }, {"SetInitTimeStep"});
    EXPECT_DEME_ERROR([&] { sim.SetInitTimeStep(std::numeric_limits<double>::quiet_NaN()); }, {"SetInitTimeStep"});
    // A rejected value is not stored: the time step is still unset (Settings::dt = -1).
    EXPECT_LE(sim.GetTimeStep(), 0.0);
}

TEST(BadInput, InitializeWithoutTimeStep) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    sim.InstructBoxDomainDimension(1, 1, 1);
    auto t = sim.LoadSphereType(1.0f, 0.01f, mat);
    sim.AddClumps(t, {make_float3(0, 0, 0)});
    EXPECT_DEME_ERROR([&] { sim.Initialize(); }, {"Initialize", "SetInitTimeStep"});
    // Fixing the input makes the same solver usable.
    sim.SetInitTimeStep(1e-5);
    EXPECT_NO_THROW(sim.Initialize());
}

TEST(BadInput, InitializeWithoutDomain) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(goodMaterial());
    auto t = sim.LoadSphereType(1.0f, 0.01f, mat);
    sim.AddClumps(t, {make_float3(0, 0, 0)});
    sim.SetInitTimeStep(1e-5);
    EXPECT_DEME_ERROR([&] { sim.Initialize(); }, {"Initialize", "InstructBoxDomainDimension"});
}

TEST(BadInput, ClumpOutsideDomain) {
    Scene1 s;
    // The box is 1 m wide centred on the origin, so x = 0.75 is outside.
    s.sim.AddClumps(s.type, {make_float3(0.75f, 0, 0)});
    EXPECT_DEME_ERROR([&] { s.sim.Initialize(); }, {"Initialize", "outside"});
}

TEST(BadInput, DoDynamicsBeforeInitialize) {
    Scene1 s;
    EXPECT_DEME_ERROR([&] { s.sim.DoDynamics(1e-3); }, {"DoDynamics", "Initialize"});
    EXPECT_DEME_ERROR([&] { s.sim.DoStepDynamics(); }, {"DoStepDynamics", "Initialize"});
}

TEST(BadInput, DoDynamicsNegativeDuration) {
    Scene1 s;
    s.sim.Initialize();
    EXPECT_DEME_ERROR([&] { s.sim.DoDynamics(-1.0); }, {"DoDynamics"});
    EXPECT_DEME_ERROR([&] { s.sim.DoDynamics(std::numeric_limits<double>::quiet_NaN()); }, {"DoDynamics"});
    EXPECT_DEME_ERROR([&] { s.sim.DoDynamics(std::numeric_limits<double>::infinity()); }, {"DoDynamics"});
    EXPECT_EQ(s.sim.GetSimTime(), 0.0);  // nothing ran
}

TEST(BadInput, SetErrorOutVelocityNonPositive) {
    DEMSolver sim;
    EXPECT_DEME_ERROR([&] { sim.SetErrorOutVelocity(0.f); }, {"SetErrorOutVelocity"});
    EXPECT_DEME_ERROR([&] { sim.SetErrorOutVelocity(-1.f); }, {"SetErrorOutVelocity"});
}

// ---------------------------------------------------------------- string options

TEST(BadInput, UnknownVerbosity) {
    DEMSolver sim;
    EXPECT_DEME_ERROR([&] { sim.SetVerbosity("LOUD"); }, {"SetVerbosity", "LOUD"});
    EXPECT_DEME_ERROR([&] { sim.SetVerbosity("quiet"); }, {"SetVerbosity", "quiet"});  // case-sensitive
    EXPECT_NO_THROW(sim.SetVerbosity("QUIET"));
}

TEST(BadInput, UnknownOutputContent) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    EXPECT_DEME_ERROR([&] { sim.SetOutputContent("VELOCITY"); }, {"SetOutputContent", "VELOCITY"});
    EXPECT_DEME_ERROR([&] { sim.SetOutputContent("XYZ|ABSV|SPIN"); }, {"SetOutputContent", "SPIN"});
    EXPECT_DEME_ERROR(
        [&] {
            sim.SetOutputContent(std::vector<std::string>{"VEL", "COLOR"});
        },
        {"SetOutputContent", "COLOR"});
    EXPECT_DEME_ERROR([&] { sim.SetOutputContent({"VEL", "COLOR"}); }, {"SetOutputContent", "COLOR"});
    EXPECT_DEME_ERROR([&] { sim.SetOutputFormat("VTK"); }, {"SetOutputFormat", "VTK"});
    EXPECT_NO_THROW(sim.SetOutputContent("XYZ ABSV|VEL"));
}

TEST(BadInput, UnknownInspectorKind) {
    Scene1 s;
    EXPECT_DEME_ERROR([&] { s.sim.CreateInspector("clump_max_x"); }, {"CreateInspector", "clump_max_x"});
    EXPECT_DEME_ERROR([&] { s.sim.CreateInspector(""); }, {"CreateInspector"});
    // A valid inspector used before Initialize is an error too.
    auto insp = s.sim.CreateInspector("clump_max_z");
    EXPECT_DEME_ERROR([&] { insp->GetValue(); }, {"DEMInspector::GetValue", "not initialized"});
}

TEST(BadInput, MalformedPrescribedExpression) {
    Scene1 s;
    EXPECT_DEME_ERROR([&] { s.sim.SetFamilyPrescribedLinVel(1, "0.1*sin(", "none", "none"); },
                      {"SetFamilyPrescribedLinVel", "0.1*sin("});
    EXPECT_DEME_ERROR([&] { s.sim.SetFamilyPrescribedLinVel(1, "none", "none", "2^t"); },
                      {"SetFamilyPrescribedLinVel"});
    EXPECT_DEME_ERROR([&] { s.sim.SetFamilyPrescribedAngVel(1, "x", "0", "0"); }, {"SetFamilyPrescribedAngVel"});
}

// ---------------------------------------------------------------- families

TEST(BadInput, FamilyOutOfRange) {
    Scene1 s;
    // Families are 0..255 (NUM_FAMILIES = 256).
    EXPECT_DEME_ERROR([&] { s.sim.SetFamilyFixed(256); }, {"SetFamilyFixed", "256"});
    EXPECT_DEME_ERROR([&] { s.sim.SetFamilyPrescribedLinVel(256, "1", "none", "none"); },
                      {"SetFamilyPrescribedLinVel", "256"});
    EXPECT_DEME_ERROR([&] { s.sim.DisableContactBetweenFamilies(0, 256); }, {"DisableContactBetweenFamilies", "256"});
    EXPECT_DEME_ERROR([&] { s.sim.ChangeFamily(256, 0); }, {"ChangeFamily", "256"});
    EXPECT_DEME_ERROR([&] { s.batch->SetFamily(256u); }, {"DEMClumpBatch::SetFamily", "256"});
    EXPECT_NO_THROW(s.sim.SetFamilyFixed(255));
}

// ---------------------------------------------------------------- trackers

TEST(BadInput, TrackerBeforeInitialize) {
    Scene1 s;
    auto tr = s.sim.Track(s.batch);
    EXPECT_DEME_ERROR([&] { tr->Pos(0); }, {"DEMTracker", "not initialized"});
    EXPECT_DEME_ERROR([&] { tr->SetVel(make_float3(1, 0, 0), 0); }, {"DEMTracker", "not initialized"});
}

TEST(BadInput, TrackerOffsetOutOfRange) {
    Scene1 s;
    auto tr = s.sim.Track(s.batch);  // tracks 1 clump: offset 0 only
    s.sim.Initialize();
    EXPECT_NO_THROW(tr->Pos(0));
    EXPECT_DEME_ERROR([&] { tr->Pos(1); }, {"DEMTracker", "offset 1"});
    EXPECT_DEME_ERROR([&] { tr->Vel(100); }, {"DEMTracker", "offset 100"});
    EXPECT_DEME_ERROR([&] { tr->SetPos(make_float3(0.1f, 0, 0), 1); }, {"DEMTracker", "offset 1"});
    EXPECT_DEME_ERROR([&] { tr->AddAcc(make_float3(0, 0, 1), 7); }, {"DEMTracker", "offset 7"});
    // Moving a tracked clump out of the domain is rejected and names the setter.
    EXPECT_DEME_ERROR([&] { tr->SetPos(make_float3(2.f, 0, 0), 0); }, {"DEMTracker::SetPos", "outside"});
    EXPECT_DEME_ERROR([&] { s.sim.Track(std::shared_ptr<DEMClumpBatch>()); }, {"Track", "null"});
}

// ---------------------------------------------------------------- batches

TEST(BadInput, BatchSetVelMismatchedSize) {
    Scene1 s;
    auto b2 = s.sim.AddClumps(s.type, {make_float3(0.1f, 0, 0), make_float3(-0.1f, 0, 0)});
    // Two clumps: one or three values are rejected.
    EXPECT_DEME_ERROR([&] { b2->SetVel(std::vector<float3>{make_float3(1, 0, 0)}); },
                      {"DEMClumpBatch::SetVel", "1 values for 2 clumps"});
    EXPECT_DEME_ERROR([&] { b2->SetVel(std::vector<float3>(3, make_float3(0.f))); },
                      {"DEMClumpBatch::SetVel", "3 values for 2 clumps"});
    EXPECT_DEME_ERROR([&] { b2->SetAngVel(std::vector<float3>(1, make_float3(0.f))); }, {"DEMClumpBatch::SetAngVel"});
    EXPECT_DEME_ERROR([&] { b2->SetOriQ(std::vector<float4>(3, make_float4(0, 0, 0, 1))); },
                      {"DEMClumpBatch::SetOriQ"});
    EXPECT_DEME_ERROR([&] { b2->SetOriQ(make_float4(0, 0, 0, 0)); }, {"DEMClumpBatch::SetOriQ"});
    EXPECT_NO_THROW(b2->SetVel(std::vector<float3>(2, make_float3(0.f))));
}

TEST(BadInput, AddClumpsMismatchedSizesAndNull) {
    Scene1 s;
    EXPECT_DEME_ERROR(
        [&] {
            s.sim.AddClumps(std::vector<std::shared_ptr<DEMClumpTemplate>>{s.type, s.type},
                            std::vector<float3>{make_float3(0.f)});
        },
        {"AddClumps", "2 templates for 1 positions"});
    EXPECT_DEME_ERROR([&] { s.sim.AddClumps(std::shared_ptr<DEMClumpTemplate>(), {make_float3(0.f)}); },
                      {"AddClumps", "null"});
    EXPECT_DEME_ERROR([&] { s.sim.AddClumps(s.type, {make_float3(std::numeric_limits<float>::quiet_NaN(), 0, 0)}); },
                      {"AddClumps", "finite"});
    // The failed calls added nothing.
    EXPECT_EQ(s.sim.GetNumClumps(), 1u);
}

// ---------------------------------------------------------------- regressions

// An Initialize that fails to start (here: SetBackend("cuda") on a machine without a usable GPU)
// leaves the scene as it was: its objects stay editable, and Initialize can be called again.
TEST(BadInputRegression, FailedInitializeCanBeRetried) {
    if (!deme::cuda::usableDevices().empty()) GTEST_SKIP() << "a GPU is present: the CUDA backend starts";
    Scene1 s;
    s.sim.SetBackend("cuda");
    EXPECT_DEME_ERROR([&] { s.sim.Initialize(); }, {"Initialize"});
    s.batch->SetVel(make_float3(1, 0, 0));  // still editable: not marked initialized
    s.sim.SetBackend("cpu");
    s.sim.Initialize();
    s.sim.DoDynamics(0.01);
    auto tr = s.sim.Track(s.batch);
    EXPECT_NEAR(tr->Pos().x, 0.01, 1e-6);  // the velocity set after the failed call moved it
}

TEST(BadInputRegression, TrackingAnotherSolversBatchIsAnError) {
    Scene1 a, b;
    a.sim.Initialize();
    EXPECT_DEME_ERROR([&] { a.sim.Track(b.batch); }, {"Track", "not added to this solver"});
}

TEST(BadInputRegression, HugeDurationIsAnError) {
    Scene1 s;
    s.sim.Initialize();
    EXPECT_DEME_ERROR([&] { s.sim.DoDynamics(1e300); }, {"DoDynamics", "too many steps"});
}
