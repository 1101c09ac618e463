// Tests written once for every backend. A test declared with DEME_BACKEND_TEST runs once per backend
// this machine has: "cpu" always, "cuda" where the library has the CUDA backend and a usable GPU is
// present. The instances are named Suite.Name/cpu and Suite.Name/cuda (gtest's value-parameterised
// tests with an empty prefix), so a filter "Suite.*" takes both and "*/cuda" the GPU's. Without a
// GPU (CI) only the CPU instances exist: nothing is skipped, and ctest counts what ran.
//
//   DEME_BACKEND_TEST_SUITE(HertzImpact);  // once per suite, in the file of its tests
//   DEME_BACKEND_TEST(HertzImpact, DurationAndPeakOverlapMatchTheory) { DEMSolver sim; ... }
//
// How an instance makes its solvers use its backend: from the fixture's construction to its
// destruction the environment variable DEME_BACKEND, the backend a solver takes unless SetBackend
// says otherwise (read at Initialize), names the instance's backend; the previous value (or its
// absence) comes back afterwards. So every solver the test creates, also in functions it calls,
// runs on the instance's backend without being told; a solver that must run on a given backend
// whatever the instance (the CPU reference of a comparison) calls SetBackend. The variable is
// changed only between tests, when no solver and none of its threads exist.
//
// backend() names the instance's backend, onGpu() says whether it is "cuda", scratchDir() is a
// directory of the test's own (removed afterwards; instances running at once do not share it).
//
// Which tests are not written this way: those that pin the CPU on purpose because they check it bit
// for bit (the CPU's threads and fixed summation order: Async.*, Determinism.*, RunMonitor.*,
// ForceModelBitIdentity.*), tests that start no simulation (input checks before Initialize, readers,
// math), tests of internals, and GpuParity.*, which compare the two backends in one test.
// All tests of a suite use one fixture (gtest's rule), so a suite is either a backend suite or not.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "ScratchDirTest.h"
#include "backend/cuda/Device.h"

namespace deme_test {

// The backends this machine can run, "cpu" first (asked once per process).
inline const std::vector<std::string>& availableBackends() {
    static const std::vector<std::string> backends = [] {
        std::vector<std::string> b{"cpu"};
        if (deme::cuda::cudaBackendBuilt() && !deme::cuda::usableDevices().empty()) b.push_back("cuda");
        return b;
    }();
    return backends;
}

// Sets an environment variable while it lives; then restores the previous value, or unsets it if
// there was none.
class ScopedEnvironmentVariable {
  public:
    ScopedEnvironmentVariable(std::string name, const std::string& value) : m_name(std::move(name)) {
        if (const char* old = std::getenv(m_name.c_str())) {
            m_had = true;
            m_old = old;
        }
        ::setenv(m_name.c_str(), value.c_str(), 1);
    }
    ~ScopedEnvironmentVariable() {
        if (m_had)
            ::setenv(m_name.c_str(), m_old.c_str(), 1);
        else
            ::unsetenv(m_name.c_str());
    }
    ScopedEnvironmentVariable(const ScopedEnvironmentVariable&) = delete;
    ScopedEnvironmentVariable& operator=(const ScopedEnvironmentVariable&) = delete;

  private:
    std::string m_name, m_old;
    bool m_had = false;
};

class BackendTest : public ::testing::TestWithParam<std::string> {
  public:
    static std::string instanceName(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

  protected:
    // gtest sets the parameter before it constructs the fixture: the variable is in place before any
    // member of a test's own fixture is built, and is restored after the last one is gone.
    BackendTest() : m_backend(GetParam()), m_environment("DEME_BACKEND", m_backend) {}
    const std::string& backend() const { return m_backend; }
    bool onGpu() const { return m_backend == "cuda"; }
    const std::filesystem::path& scratchDir() {
        if (!m_scratch) m_scratch.reset(new ScratchDir());
        return m_scratch->path();
    }

  private:
    std::string m_backend;
    ScopedEnvironmentVariable m_environment;
    std::unique_ptr<ScratchDir> m_scratch;
};

}  // namespace deme_test

#define DEME_BACKEND_TEST_SUITE(Suite)                                                       \
    class Suite : public ::deme_test::BackendTest {};                                        \
    INSTANTIATE_TEST_SUITE_P(, Suite, ::testing::ValuesIn(::deme_test::availableBackends()), \
                             ::deme_test::BackendTest::instanceName)

#define DEME_BACKEND_TEST(Suite, Name) TEST_P(Suite, Name)
