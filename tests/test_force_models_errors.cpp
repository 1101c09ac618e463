// Errors of custom force models: code that does not compile names the line of the user's code, and
// bad use of the model and wildcard API is a deme::Error naming the call.
#include <gtest/gtest.h>

#include <fstream>

#include "BackendFixture.h"
#include "ForceModelTestUtil.h"

using namespace deme;
using namespace deme_test;

// Initialize compiles the model for the instance's backend (on the GPU also with NVRTC) and checks
// the names: every test here starts a simulation or tries to, except ForceModelHandle.*.
DEME_BACKEND_TEST_SUITE(ForceModelErrors);
DEME_BACKEND_TEST_SUITE(ForceModelErrorFiles);

namespace {

std::map<std::string, double> hertzMaterial() { return {{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}}; }

// One sphere on a floor; `code` is the force model (null: the default one).
struct OneSphere {
    DEMSolver sim;
    std::shared_ptr<DEMMaterial> mat;
    std::shared_ptr<DEMForceModel> model;
    explicit OneSphere(const char* code = nullptr) {
        sim.SetVerbosity("QUIET");
        mat = sim.LoadMaterial(hertzMaterial());
        if (code) model = sim.DefineContactForceModel(code);
        sim.InstructBoxDomainDimension(1, 1, 1);
        sim.AddBCPlane(make_float3(0, 0, -0.5f), make_float3(0, 0, 1), mat);
        sim.AddClumps(sim.LoadSphereType(1.f, 0.01f, mat), {make_float3(0, 0, 0)});
        sim.SetInitTimeStep(1e-5);
    }
};

// A model that reads nothing, with one wildcard of each kind; all tests that need an initialised
// custom model share it (one compilation, then the cache).
const char* const kQuiet = "force += make_float3(0.f, 0.f, 0.f);";
void declareQuietWildcards(DEMForceModel& m) {
    m.SetPerContactWildcards({"c"});
    m.SetPerOwnerWildcards({"Q"});
    m.SetPerGeometryWildcards({"g"});
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

// Test 7 of the issue: a syntax error and an unknown variable, each reported with the line of the
// snippet (the snippet is compiled as "force_model", see docs/force-models.md).
DEME_BACKEND_TEST(ForceModelErrors, SyntaxErrorNamesTheLine) {
    OneSphere s(
        "const float k = 1e5f;\n"
        "const float f = k * (float)overlapDepth;\n"
        "force += f * B2A +;\n"  // an operand missing
        "torque_only_force = make_float3(0.f);\n");
    const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
    EXPECT_TRUE(contains(msg, "Initialize")) << msg;
    EXPECT_TRUE(contains(msg, "force_model:3:")) << msg;
    EXPECT_TRUE(contains(msg, "error")) << msg;
}

DEME_BACKEND_TEST(ForceModelErrors, UnknownVariableNamesTheLine) {
    OneSphere s(
        "const float k = 1e5f;\n"
        "force += k * stifness * B2A;\n");
    const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
    EXPECT_TRUE(contains(msg, "force_model:2:")) << msg;
    EXPECT_TRUE(contains(msg, "stifness")) << msg;
    // The solver is not initialised: a fixed model can be tried again.
    s.sim.DefineContactForceModel("force += 1e5f * (float)overlapDepth * B2A;");
    EXPECT_NO_THROW(s.sim.Initialize());
}

// A model read from a file is reported under the file's name.
DEME_BACKEND_TEST(ForceModelErrorFiles, ReadModelErrorsNameTheFile) {
    const std::filesystem::path dir = scratchDir();
    const std::string path = (dir / "my_model.cpp").string();
    std::ofstream(path) << "// a comment\nforce += undefinedThing;\n";
    OneSphere s;
    s.sim.ReadContactForceModel(path);
    const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
    EXPECT_TRUE(contains(msg, "my_model.cpp:2:")) << msg;
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.ReadContactForceModel((dir / "none.cpp").string()); }),
                         "ReadContactForceModel"));
}

// The model handle's own checks, before any simulation: a plain test.
TEST(ForceModelHandle, NamesAreChecked) {
    OneSphere s(kQuiet);
    DEMForceModel& m = *s.model;
    for (const char* bad : {"1Q", "Q-1", "", "a b"})
        EXPECT_TRUE(contains(demeErrorMessage([&] { m.SetPerOwnerWildcards({bad}); }), "not a C++ identifier"));
    // Names every model already has (paper Table 3), keywords, helpers.
    for (const char* taken : {"force", "overlapDepth", "AOwner", "persistent", "E_eff", "float", "dot", "deme_x"}) {
        const std::string msg = demeErrorMessage([&] { m.SetPerContactWildcards({taken}); });
        EXPECT_TRUE(contains(msg, "DEMForceModel::SetPerContactWildcards")) << msg;
        EXPECT_TRUE(contains(msg, taken)) << msg;
    }
    EXPECT_TRUE(contains(demeErrorMessage([&] { m.SetPerGeometryWildcards({"a", "a"}); }), "twice"));
    // The built-in models' inputs are fixed.
    auto builtIn = s.sim.UseFrictionalHertzianModel();
    EXPECT_TRUE(contains(demeErrorMessage([&] { builtIn->SetPerOwnerWildcards({"Q"}); }), "built-in"));
    // Which pairs a model sees: a custom model every pair unless told otherwise, a built-in one only
    // pairs that touch, fixed.
    EXPECT_TRUE(m.GetCalledForApartPairs());
    EXPECT_FALSE(builtIn->GetCalledForApartPairs());
    const std::string msg = demeErrorMessage([&] { builtIn->SetCalledForApartPairs(true); });
    EXPECT_TRUE(contains(msg, "DEMForceModel::SetCalledForApartPairs")) << msg;
    EXPECT_TRUE(contains(msg, "built-in")) << msg;
}

DEME_BACKEND_TEST(ForceModelErrors, NamesMustNotClash) {
    {
        OneSphere s(kQuiet);
        s.model->SetPerOwnerWildcards({"mu"});  // also a material property
        const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
        EXPECT_TRUE(contains(msg, "\"mu\"") && contains(msg, "twice")) << msg;
    }
    {
        OneSphere s(kQuiet);
        s.model->SetPerOwnerWildcards({"w"});
        s.model->SetPerGeometryWildcards({"w"});
        EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.Initialize(); }), "\"w\""));
    }
    {
        OneSphere s(kQuiet);
        s.sim.LoadMaterial({{"ts", 1.0}});  // a material property hiding the time step
        const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
        EXPECT_TRUE(contains(msg, "material property \"ts\"")) << msg;
    }
}

DEME_BACKEND_TEST(ForceModelErrors, MissingMaterialPropertiesNameMaterialAndProperty) {
    {
        OneSphere s(kQuiet);
        s.model->SetMustHaveMatProp({"E", "hardness"});
        const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
        EXPECT_TRUE(contains(msg, "Initialize") && contains(msg, "material 0") && contains(msg, "\"hardness\"")) << msg;
    }
    {
        OneSphere s(kQuiet);
        s.sim.LoadMaterial({{"W", 1.0}});  // material 1 has W, material 0 does not
        s.model->SetMustPairwiseMatProp({"W"});
        const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
        EXPECT_TRUE(contains(msg, "materials 0 and 0") && contains(msg, "\"W\"")) << msg;
    }
    {
        // A pair value for a property the model reads per material.
        OneSphere s(kQuiet);
        auto other = s.sim.LoadMaterial(hertzMaterial());
        s.sim.SetMaterialPropertyPair("E", s.mat, other, 1e7);
        const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
        EXPECT_TRUE(contains(msg, "SetMaterialPropertyPair") && contains(msg, "\"E\"")) << msg;
    }
}

DEME_BACKEND_TEST(ForceModelErrors, WildcardCallsBeforeInitialize) {
    OneSphere s(kQuiet);
    declareQuietWildcards(*s.model);
    const std::vector<std::function<void()>> calls = {
        [&] { s.sim.SetOwnerWildcardValue("Q", 0, 1.f); },
        [&] { s.sim.GetOwnerWildcardValue("Q", 0); },
        [&] { s.sim.SetSphereWildcardValue("g", 0, 1.f); },
        [&] { s.sim.GetSphereWildcardValue("g", 0); },
        [&] { s.sim.SetAnalWildcardValue("g", 0, 1.f); },
        [&] { s.sim.SetContactWildcardValue("c", 1.f); },
        [&] { s.sim.SetFamilyContactWildcardValue(0, 1, "c", 1.f); },
        [&] { s.sim.MarkPersistentContact(); },
        [&] { s.sim.RemoveFamilyPersistentContactBoth(0); },
    };
    for (const auto& call : calls) EXPECT_TRUE(contains(demeErrorMessage(call), "after Initialize()"));
    // Rules for later are fine before Initialize, but their names are checked then.
    s.sim.SetFamilyOwnerWildcardValue(0, "q", 1.f);
    const std::string msg = demeErrorMessage([&] { s.sim.Initialize(); });
    EXPECT_TRUE(contains(msg, "SetFamilyOwnerWildcardValue") && contains(msg, "\"q\"")) << msg;
}

DEME_BACKEND_TEST(ForceModelErrors, UnknownWildcardNamesAndIds) {
    OneSphere s(kQuiet);
    declareQuietWildcards(*s.model);
    s.sim.Initialize();
    std::string msg = demeErrorMessage([&] { s.sim.SetOwnerWildcardValue("charge", 0, 1.f); });
    EXPECT_TRUE(contains(msg, "SetOwnerWildcardValue") && contains(msg, "\"charge\"") && contains(msg, "Q")) << msg;
    msg = demeErrorMessage([&] { s.sim.GetSphereWildcardValue("Q", 0); });  // Q is an owner wildcard
    EXPECT_TRUE(contains(msg, "GetSphereWildcardValue") && contains(msg, "geometry wildcard \"Q\"")) << msg;
    EXPECT_TRUE(
        contains(demeErrorMessage([&] { s.sim.SetFamilyContactWildcardValue(0, 0, "Q", 1.f); }), "contact wildcard"));
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.SetFamilyContactWildcardInitValue(0, 0, "x", 1.f); }),
                         "SetFamilyContactWildcardInitValue"));
    // Owner 0 is the plane, 1 the sphere: 2 owners; one sphere; one analytical component.
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.SetOwnerWildcardValue("Q", 2, 1.f); }), "out of range"));
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.SetOwnerWildcardValue("Q", 1, {1.f, 2.f}); }), "out of range"));
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.GetSphereWildcardValue("g", 1); }), "out of range"));
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.SetTriWildcardValue("g", 0, 1.f); }), "out of range"));
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.SetOwnerWildcardValue("Q", 0, NAN); }), "finite"));
    // Valid calls work, and the model is fixed now.
    s.sim.SetAnalWildcardValue("g", 0, 4.f);
    EXPECT_EQ(s.sim.GetAnalWildcardValue("g", 0), 4.f);
    s.sim.SetSphereWildcardValue("g", 0, 5.f);
    EXPECT_EQ(s.sim.GetSphereWildcardValue("g", 0), 5.f);
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.model->SetPerOwnerWildcards({"R"}); }), "before Initialize()"));
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.model->SetCalledForApartPairs(false); }), "before Initialize()"));
    EXPECT_TRUE(contains(demeErrorMessage([&] { s.sim.DefineContactForceModel(kQuiet); }), "DefineContactForceModel"));
}

// With the built-in model there are no wildcards to set.
DEME_BACKEND_TEST(ForceModelErrors, DefaultModelHasNoOwnerWildcards) {
    OneSphere s;
    s.sim.Initialize();
    const std::string msg = demeErrorMessage([&] { s.sim.SetOwnerWildcardValue("Q", 0, 1.f); });
    EXPECT_TRUE(contains(msg, "no owner wildcard \"Q\" (it has none")) << msg;
}
