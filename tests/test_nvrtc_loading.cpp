// NVRTC is loaded when the CUDA backend first compiles, not when a process of a build with CUDA
// starts (backend/cuda/NvrtcLibrary.h): linked, its library took 28 MB of resident memory in every
// process, runs on the CPU backend included. Each check runs in a fresh process (a death test's
// child, re-executed), since this runner's other tests load NVRTC.
#include <gtest/gtest.h>

#include <cstdlib>

#include "TestHelpers.h"

#if DEME_TESTS_CUDA_BUILT
#include "backend/cuda/NvrtcCompiler.h"

using namespace deme;
using namespace deme_test;

namespace {

// A few spheres falling onto the floor on the CPU backend: Initialize and a hundred steps.
void runOnTheCpu() {
    DEMSolver sim;
    sim.SetBackend("cpu");
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.4, 0.5, 0.01));
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    sim.InstructBoxDomainBoundingBC("top_open", mat);
    auto sphere = sim.LoadSphereType(1e-3f, 0.005f, mat);
    sim.AddClumps(sphere, {make_float3(0, 0, 0), make_float3(0.011f, 0, 0), make_float3(0, 0.011f, 0.02f)});
    sim.SetInitTimeStep(1e-5);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.Initialize();
    sim.DoDynamics(1e-3);
}

}  // namespace

TEST(NvrtcLoading, ACpuRunLoadsNoNvrtcAndTheFirstCompileDoes) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            runOnTheCpu();
            std::exit(cuda::nvrtcIsLoaded() ? 1 : 0);
        },
        testing::ExitedWithCode(0), "");
    EXPECT_EXIT(
        {
            const bool before = cuda::nvrtcIsLoaded();
            const std::string version = cuda::nvrtcVersionString();  // as a compile's cache key asks
            std::exit(!before && cuda::nvrtcIsLoaded() && version != "unknown" ? 0 : 1);
        },
        testing::ExitedWithCode(0), "");
}
#endif
