// The backend fixture itself (BackendFixture.h): each instance's solvers run on its backend, and the
// environment it changes comes back as it was.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "BackendFixture.h"
#include "TestHelpers.h"

using namespace deme;
using namespace deme_test;

DEME_BACKEND_TEST_SUITE(BackendFixture);

// A solver that is not told its backend runs on the instance's: on a GPU machine "auto" would take
// CUDA for the CPU instance, so this fails there if the fixture's setting does not reach Initialize.
DEME_BACKEND_TEST(BackendFixture, SolversRunOnTheInstanceBackend) {
    const char* env = std::getenv("DEME_BACKEND");
    ASSERT_NE(env, nullptr);
    EXPECT_EQ(std::string(env), backend());
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
    sim.InstructBoxDomainDimension(1, 1, 1);
    sim.AddClumps(sim.LoadSphereType(1.f, 0.05f, mat), {make_float3(0, 0, 0)});
    sim.SetInitTimeStep(1e-4);
    sim.Initialize();
    EXPECT_EQ(sim.GetBackend(), backend());
    EXPECT_EQ(onGpu(), backend() == "cuda");
    // The scratch directory is the test's own and exists while it runs.
    EXPECT_TRUE(std::filesystem::is_directory(scratchDir()));
    EXPECT_NE(scratchDir().filename().string().find(backend()), std::string::npos) << scratchDir();
}

// What the fixture does around each test: the previous value comes back, and a variable that was not
// set is unset again.
TEST(ScopedEnvironment, RestoresThePreviousValueOrItsAbsence) {
    const char* name = "DEME_TEST_SCOPED_VARIABLE";
    ::unsetenv(name);
    {
        ScopedEnvironmentVariable outer(name, "outer");
        EXPECT_STREQ(std::getenv(name), "outer");
        {
            ScopedEnvironmentVariable inner(name, "inner");
            EXPECT_STREQ(std::getenv(name), "inner");
        }
        EXPECT_STREQ(std::getenv(name), "outer");
    }
    EXPECT_EQ(std::getenv(name), nullptr);
}
