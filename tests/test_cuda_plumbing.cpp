// Tests of the CUDA backend's plumbing that need no GPU (they run in CI): NVRTC compilation of the
// kernels and physics headers to PTX, its cache and its error messages, the device query on a
// machine without a GPU or driver, and the choice of backend. Tests that need a GPU are in
// test_cuda_gpu.cpp. In a library built without CUDA the NVRTC tests are skipped.
#include <gtest/gtest.h>

#include <deme/Error.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>

#include "BackendFixture.h"
#include "ScratchDirTest.h"
#include "TestHelpers.h"
#include "TestKernels.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "jit/EmbeddedSources.h"
#include "backend/BackendSelection.h"
#include "codegen/FamilyMotionSource.h"
#include "runtime/FamilyRules.h"

using namespace deme;
using namespace deme::cuda;

namespace {

const char* const kExamplePath = deme_test::kExampleKernelPath;
const char* const kExampleEntry = "exampleSpherePairOverlap";

void reportTime(const std::string& what, double seconds) {
    std::cout << "[   cuda   ] " << what << ": " << seconds << " s" << std::endl;
}

// Every NVRTC test gets its own cache directory, so a cache hit can only come from the test itself.
class CudaNvrtc : public deme_test::ScratchDirTest {
  protected:
    void SetUp() override {
        if (!cudaBackendBuilt()) GTEST_SKIP() << "the library was built without the CUDA backend";
        ScratchDirTest::SetUp();
        cache.emplace(dir.string());
    }
    CudaCompileResult compile(const std::string& name, const std::string& source, const std::string& arch,
                              std::vector<std::string> defines = {}) {
        CudaCompileOptions options;
        options.architecture = arch;
        options.defines = std::move(defines);
        return compileCudaSource("test", name, source, options, *cache);
    }
    std::optional<jit::KernelCache> cache;
};

}  // namespace

// ---- NVRTC

TEST_F(CudaNvrtc, CompilesTheExampleKernelToPtx) {
    const CudaCompileResult r = compile(kExamplePath, deme_test::testKernelText("Example.cu"), "compute_90");
    EXPECT_EQ(r.kind, GpuImageKind::Ptx);
    EXPECT_EQ(r.architecture, "compute_90");
    EXPECT_FALSE(r.cacheHit);
    EXPECT_GT(r.compileSeconds, 0.0);
    EXPECT_NE(r.image.find(".target sm_90"), std::string::npos);
    EXPECT_NE(r.image.find(".entry " + std::string(kExampleEntry)), std::string::npos) << r.image.substr(0, 2000);
    reportTime("NVRTC, example kernel to PTX, cold (NVRTC " + nvrtcVersionString() + ")", r.compileSeconds);
}

TEST_F(CudaNvrtc, SecondCompileIsACacheHit) {
    const std::string source = deme_test::testKernelText("Example.cu");
    const auto start = std::chrono::steady_clock::now();
    const CudaCompileResult first = compile(kExamplePath, source, "compute_90");
    const double cold = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto again = std::chrono::steady_clock::now();
    const CudaCompileResult second = compile(kExamplePath, source, "compute_90");
    const double cached = std::chrono::duration<double>(std::chrono::steady_clock::now() - again).count();
    EXPECT_FALSE(first.cacheHit);
    EXPECT_TRUE(second.cacheHit);
    EXPECT_EQ(second.compileSeconds, 0.0);
    EXPECT_EQ(second.key, first.key);
    EXPECT_EQ(second.image, first.image);
    EXPECT_EQ(cache->stats().published, 1u);
    reportTime("NVRTC example kernel, cold call", cold);
    reportTime("NVRTC example kernel, cached call", cached);
}

TEST_F(CudaNvrtc, OptionsArchitectureAndSourceAreInTheKey) {
    const std::string source = deme_test::testKernelText("Example.cu");
    const std::string base = compile(kExamplePath, source, "compute_90").key;
    EXPECT_NE(compile(kExamplePath, source, "compute_90", {"DEME_EXAMPLE_FLAG=1"}).key, base);
    EXPECT_NE(compile(kExamplePath, source, "compute_80").key, base);
    EXPECT_NE(compile(kExamplePath, source + "\n// changed\n", "compute_90").key, base);
    EXPECT_EQ(cache->stats().published, 4u);
}

// DEME_CUDA_DEFINES (a diagnostic switch: one binary times variants of a kernel) reaches every
// compile as macros, and is in the cache key: a source that compiles only with the macros set.
TEST_F(CudaNvrtc, DefinesFromTheEnvironmentReachEveryCompile) {
    const std::string source =
        "#if !defined(DEME_TEST_A) || DEME_TEST_B != 7\n#error macros missing\n#endif\n"
        "extern \"C\" __global__ void k(float* x) { x[0] = 1.f; }\n";
    const std::string without = deme_test::demeErrorMessage([&] { compile("defines.cu", source, "compute_90"); });
    EXPECT_NE(without.find("macros missing"), std::string::npos) << without;
    deme_test::ScopedEnvironmentVariable defines("DEME_CUDA_DEFINES", " DEME_TEST_A  DEME_TEST_B=7 ");
    const CudaCompileResult with = compile("defines.cu", source, "compute_90");
    EXPECT_FALSE(with.cacheHit);
    EXPECT_NE(with.image.find(".entry k"), std::string::npos);
}

// CUBIN needs no GPU either: NVRTC assembles it itself.
TEST_F(CudaNvrtc, CompilesCubinForARealArchitecture) {
    const CudaCompileResult r = compile(kExamplePath, deme_test::testKernelText("Example.cu"), "sm_90");
    EXPECT_EQ(r.kind, GpuImageKind::Cubin);
    ASSERT_GE(r.image.size(), 4u);
    EXPECT_EQ(r.image.substr(0, 4),
              "\x7f"
              "ELF");
    reportTime("NVRTC example kernel to sm_90 CUBIN, cold", r.compileSeconds);
}

// The CI check that every kernel of src/backend/cuda/kernels/ compiles.
TEST_F(CudaNvrtc, EveryEmbeddedKernelCompiles) {
    const std::string folder = "backend/cuda/kernels/";
    int compiled = 0;
    for (const jit::EmbeddedFile& f : jit::embeddedSources()) {
        const std::string path = f.path;
        if (path.rfind(folder, 0) != 0 || path.size() < 3 || path.compare(path.size() - 3, 3, ".cu") != 0) continue;
        SCOPED_TRACE(path);
        EXPECT_NO_THROW({
            try {
                compile(path, std::string(f.text, f.size), "compute_90");
            } catch (const deme::Error& e) {
                ADD_FAILURE() << e.what();
            }
        });
        compiled++;
    }
    EXPECT_GE(compiled, 1) << "no kernels embedded under " << folder;
}

// The families' prescriptions as generated source: every function the expression language has, fixed
// families and all six components, compile for sm_90 (the GPU evaluates them each step).
TEST_F(CudaNvrtc, FamilyPrescriptionsCompile) {
    FamilyRules rules;
    const char* const texts[] = {"0.1*sin(t) + cos(t) - tan(t)", "asin(0.5)*acos(t)*atan(t)", "sinh(t)/cosh(t)+tanh(t)",
                                 "exp(t)*log(1+t)+log10(2+t)", "sqrt(t)+abs(-t)+fabs(t)+floor(t)+ceil(t)",
                                 "atan2(t, 1) + pow(t, 2) + fmin(t, 1) + fmax(t, 0) + min(t, 1) + max(t, 0) + fmod(t, 1)"};
    for (unsigned int f = 0; f < 6; f++) {
        FamilyMotion& m = rules.motion(f + 1);
        for (int i = 0; i < 3; i++) {
            m.linPrescribed[i] = m.angPrescribed[i] = true;
            m.lin[i] = Expression::parse(texts[(f + i) % 6], {"t"}, "test");
            m.ang[i] = Expression::parse(texts[(f + i + 1) % 6], {"t"}, "test");
        }
    }
    rules.motion(255).fixed = true;
    const std::string source = familyMotionKernelSource(rules.motions());
    EXPECT_NE(source.find("case 255:"), std::string::npos);
    EXPECT_NE(source.find("s.fixed = 1;"), std::string::npos);
    try {
        const CudaCompileResult r = compile("deme_family_motion.cu", source, "compute_90");
        EXPECT_NE(r.image.find(kFamilyMotionKernel), std::string::npos);
    } catch (const deme::Error& e) {
        ADD_FAILURE() << e.what() << "\n" << source;
    }
}

// Every single-source physics header compiles for the device, the default force model (with its
// logf, powf, sqrtf) included, and deme's vector types keep their host layout there.
TEST_F(CudaNvrtc, PhysicsHeadersCompileForTheDevice) {
    const std::string source = R"(
#include "physics/CompactPosition.h"
#include "physics/ContactGeometry.h"
#include "physics/BuiltInForceModels.h"
#include "physics/MaterialMixing.h"
#include "physics/RigidBody.h"

static_assert(sizeof(deme::float3) == 12 && alignof(deme::float3) == 4, "host layout");
static_assert(sizeof(deme::float4) == 16 && alignof(deme::float4) == 4, "host layout, unlike CUDA's float4");
static_assert(sizeof(deme::double3) == 24, "host layout");
static_assert(sizeof(uint64_t) == 8 && sizeof(int64_t) == 8 && sizeof(uint16_t) == 2 && sizeof(uint8_t) == 1, "");

namespace deme {
__global__ void forceKernel(const ContactInputs* in, FrictionalHertzModel model, float* wildcards, float3* force,
                            float3* torqueOnlyForce, unsigned int n) {
    const unsigned int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    float3 f = make_float3(0.f), t = make_float3(0.f), couple = make_float3(0.f);
    bool persistent = false;
    model(in[i], wildcards + FrictionalHertzModel::kNumContactWildcards * i, f, t, couple, persistent);
    force[i] = f;
    torqueOnlyForce[i] = t;
}
}  // namespace deme

extern "C" __global__ void physicsSmoke(double* out, deme::float4* q, deme::float3 w, float dt) {
    using deme::double3;
    const deme::ContactPoint c = deme::sphereCylinderContact(deme::make_double3(0.1, 0, 0), 0.01,
        deme::make_double3(0, 0, 0), deme::make_double3(0, 0, 1), 1.0, true);
    q[0] = deme::integrateOrientation(q[0], w, dt);
    const deme::float3 wv =
        deme::advanceAngularVelocity(w, w, deme::make_float3(1.f), deme::make_float3(1.f), dt).wEnd;
    deme::voxelID_t v; deme::subVoxelPos_t sx, sy, sz;
    deme::DomainFrame frame{deme::make_double3(0, 0, 0), 1.0, 1.0 / 65536};
    deme::encodePosition(c.point, frame, v, sx, sy, sz);
    out[0] = c.overlap + deme::dampingBetaFromCoR(0.5f) + (double)v + wv.x;
}
)";
    const CudaCompileResult r = compile("physics_smoke", source, "compute_90");
    EXPECT_NE(r.image.find(".entry physicsSmoke"), std::string::npos);
}

// Quoted includes resolve as in the library's own build: next to the including file (here the
// program itself, named as if it lived in physics/), then at the include root.
TEST_F(CudaNvrtc, QuotedIncludesResolveNextToTheIncluderFirst) {
    const std::string source =
        "#include \"Quaternion.h\"\n"
        "#include \"deme/VariableTypes.h\"\n"
        "extern \"C\" __global__ void relative(deme::float4* q) { q[0] = deme::quatNormalize(q[0]); }\n";
    EXPECT_NO_THROW(compile("physics/relative_include_test.cu", source, "compute_90"));
    const std::string msg = deme_test::demeErrorMessage([&] { compile("elsewhere/relative_include_test.cu", source, "compute_90"); });
    EXPECT_NE(msg.find("Quaternion.h"), std::string::npos) << msg;
}

TEST_F(CudaNvrtc, ErrorsPointIntoTheMarkedSnippet) {
    const std::string source =
        "#include \"physics/Quaternion.h\"\n"
        "extern \"C\" __global__ void k(float* out) {\n"
        "#line 1 \"force_model\"\n"
        "    float x = 1.f +;\n"
        "    out[0] = x;\n"
        "}\n";
    const std::string msg = deme_test::demeErrorMessage([&] { compile("generated_force_kernel", source, "compute_90"); });
    EXPECT_EQ(msg.rfind("test: ", 0), 0u) << msg;  // names the call
    EXPECT_NE(msg.find("force_model:1: error"), std::string::npos) << msg;
    EXPECT_NE(msg.find("generated_force_kernel"), std::string::npos) << msg;
    EXPECT_NE(msg.find("NVRTC"), std::string::npos) << msg;
    EXPECT_TRUE(cache->stats().published == 0u);
}

TEST_F(CudaNvrtc, LongLogsAreCut) {
    std::string source = "extern \"C\" __global__ void k() {\n";
    for (int i = 0; i < 60; i++) source += "  undefined_" + std::to_string(i) + " = 1;\n";
    source += "}\n";
    const std::string msg = deme_test::demeErrorMessage([&] { compile("many_errors", source, "compute_90"); });
    EXPECT_NE(msg.find("more lines]"), std::string::npos) << msg;
}

TEST_F(CudaNvrtc, UnknownArchitectureIsAnError) {
    const std::string msg = deme_test::demeErrorMessage([&] { compile("k", "__global__ void k() {}", "gfx90a"); });
    EXPECT_NE(msg.find("gfx90a"), std::string::npos) << msg;
}

TEST_F(CudaNvrtc, NoArchitectureAndNoGpuIsAnError) {
    if (!usableDevices().empty()) GTEST_SKIP() << "a GPU is present: the architecture is the GPU's";
    const std::string msg = deme_test::demeErrorMessage([&] { compile("k", "__global__ void k() {}", ""); });
    EXPECT_NE(msg.find("no usable GPU"), std::string::npos) << msg;
}

TEST(CudaNotBuilt, CallsSaySoWhenTheBackendIsMissing) {
    if (cudaBackendBuilt()) GTEST_SKIP() << "the CUDA backend is built";
    const std::string msg = deme_test::demeErrorMessage([] { compileCudaSource("Compile", "k", "", {}); });
    EXPECT_NE(msg.find("not built"), std::string::npos) << msg;
    EXPECT_NE(queryDevices().whyNone.find("not built"), std::string::npos);
    EXPECT_THROW(DeviceBuffer<int>(4), deme::Error);
    EXPECT_EQ(deviceBytesAllocated(), 0u);
}

// ---- the device query on any machine

TEST(CudaDevices, QueryNeverThrowsAndExplainsAnEmptyAnswer) {
    const DeviceQuery* q = nullptr;
    EXPECT_NO_THROW(q = &queryDevices());
    ASSERT_NE(q, nullptr);
    EXPECT_EQ(&usableDevices(), &q->usable);
    if (q->usable.empty()) {
        EXPECT_FALSE(q->whyNone.empty());
        std::cout << "[   cuda   ] no usable GPU: " << q->whyNone << std::endl;
    }
    for (const DeviceInfo& d : q->usable) {
        EXPECT_FALSE(d.name.empty());
        EXPECT_GT(d.totalMemoryBytes, 0u);
        EXPECT_GT(d.multiprocessors, 0);
        EXPECT_EQ(d.architecture(), "sm_" + std::to_string(d.major) + std::to_string(d.minor));
        std::cout << "[   cuda   ] GPU " << d.id << ": " << d.name << ", " << d.architecture() << std::endl;
    }
}

// Without a GPU (or driver) an allocation is a deme::Error, not a crash.
TEST(CudaDevices, AllocatingWithoutAGpuThrows) {
    if (!usableDevices().empty()) GTEST_SKIP() << "a GPU is present";
    EXPECT_THROW(DeviceBuffer<float>(16), deme::Error);
    DeviceBuffer<float> empty;
    EXPECT_NO_THROW(empty.resize(0));  // nothing to allocate
    EXPECT_EQ(deviceBytesAllocated(), 0u);
}

// ---- backend selection

TEST(CudaBackendSelection, ParsesTheThreeNames) {
    EXPECT_EQ(parseBackendRequest("t", "cpu"), BackendRequest::Cpu);
    EXPECT_EQ(parseBackendRequest("t", " CUDA "), BackendRequest::Cuda);
    EXPECT_EQ(parseBackendRequest("t", "Auto"), BackendRequest::Auto);
    const std::string msg = deme_test::demeErrorMessage([] { parseBackendRequest("SetBackend", "gpu"); });
    EXPECT_EQ(msg.rfind("SetBackend: ", 0), 0u) << msg;
    EXPECT_NE(msg.find("\"gpu\""), std::string::npos) << msg;
    EXPECT_NE(msg.find("cpu, cuda, auto"), std::string::npos) << msg;
    EXPECT_THROW(parseBackendRequest("t", ""), deme::Error);
}

TEST(CudaBackendSelection, ReadsTheEnvironment) {
    const char* old = std::getenv("DEME_BACKEND");
    const std::string saved = old ? old : "";
    unsetenv("DEME_BACKEND");
    EXPECT_EQ(backendRequestFromEnvironment(), BackendRequest::Auto);
    setenv("DEME_BACKEND", "", 1);
    EXPECT_EQ(backendRequestFromEnvironment(), BackendRequest::Auto);
    setenv("DEME_BACKEND", "cpu", 1);
    EXPECT_EQ(backendRequestFromEnvironment(), BackendRequest::Cpu);
    setenv("DEME_BACKEND", "opencl", 1);
    const std::string msg = deme_test::demeErrorMessage([] { backendRequestFromEnvironment(); });
    EXPECT_EQ(msg.rfind("DEME_BACKEND: ", 0), 0u) << msg;
    if (old)
        setenv("DEME_BACKEND", saved.c_str(), 1);
    else
        unsetenv("DEME_BACKEND");
}

namespace {

CudaAvailability withGpu() {
    DeviceInfo d;
    d.id = 1;
    d.name = "Test GPU";
    d.major = 9;
    d.totalMemoryBytes = size_t(80) << 30;
    d.multiprocessors = 132;
    return CudaAvailability{true, {d}, ""};
}
const CudaAvailability kNoDriver{true, {}, "no CUDA driver is installed (libcuda.so.1 was not found)"};
const CudaAvailability kNotBuilt{false, {}, "the CUDA backend was not built into this library"};

}  // namespace

TEST(CudaBackendSelection, CpuAlwaysWorks) {
    for (const CudaAvailability& a : {withGpu(), kNoDriver, kNotBuilt}) {
        const BackendChoice c = resolveBackend("t", BackendRequest::Cpu, a);
        EXPECT_EQ(c.kind, BackendKind::Cpu);
        EXPECT_EQ(c.deviceId, -1);
        EXPECT_NE(c.reason.find("requested"), std::string::npos) << c.reason;
    }
    EXPECT_EQ(resolveBackend("t", BackendRequest::Cpu).kind, BackendKind::Cpu);  // this machine, any build
}

TEST(CudaBackendSelection, AutoFallsBackToTheCpuAndSaysWhy) {
    std::vector<std::pair<Verbosity, std::string>> logged;
    const BackendLogger log = [&](Verbosity v, const std::string& m) { logged.emplace_back(v, m); };

    const BackendChoice noDriver = resolveBackend("t", BackendRequest::Auto, kNoDriver, log);
    EXPECT_EQ(noDriver.kind, BackendKind::Cpu);
    EXPECT_NE(noDriver.reason.find("no usable GPU: no CUDA driver"), std::string::npos) << noDriver.reason;

    const BackendChoice notBuilt = resolveBackend("t", BackendRequest::Auto, kNotBuilt, log);
    EXPECT_EQ(notBuilt.kind, BackendKind::Cpu);
    EXPECT_NE(notBuilt.reason.find("CUDA backend was not built"), std::string::npos) << notBuilt.reason;

    ASSERT_EQ(logged.size(), 2u);
    EXPECT_EQ(logged[0].first, Verbosity::INFO);
    EXPECT_EQ(logged[0].second, noDriver.reason);
}

TEST(CudaBackendSelection, AutoTakesAUsableGpu) {
    const BackendChoice c = resolveBackend("t", BackendRequest::Auto, withGpu());
    EXPECT_EQ(c.kind, BackendKind::Cuda);
    EXPECT_EQ(c.deviceId, 1);
    EXPECT_NE(c.reason.find("Test GPU"), std::string::npos) << c.reason;
    EXPECT_STREQ(backendName(c.kind), "cuda");
}

TEST(CudaBackendSelection, CudaWithoutAGpuIsAnError) {
    const std::string noDriver = deme_test::demeErrorMessage([] { resolveBackend("Initialize", BackendRequest::Cuda, kNoDriver); });
    EXPECT_EQ(noDriver.rfind("Initialize: ", 0), 0u) << noDriver;
    EXPECT_NE(noDriver.find("no CUDA driver"), std::string::npos) << noDriver;
    const std::string notBuilt = deme_test::demeErrorMessage([] { resolveBackend("Initialize", BackendRequest::Cuda, kNotBuilt); });
    EXPECT_NE(notBuilt.find("not built"), std::string::npos) << notBuilt;
    EXPECT_EQ(resolveBackend("t", BackendRequest::Cuda, withGpu()).kind, BackendKind::Cuda);
}

// The real machine: whatever it has, auto and cuda agree with the device query.
TEST(CudaBackendSelection, ThisMachine) {
    const BackendChoice a = resolveBackend("t", BackendRequest::Auto);
    std::cout << "[   cuda   ] auto: " << a.reason << std::endl;
    if (usableDevices().empty()) {
        EXPECT_EQ(a.kind, BackendKind::Cpu);
        EXPECT_THROW(resolveBackend("t", BackendRequest::Cuda), deme::Error);
    } else {
        EXPECT_EQ(a.kind, BackendKind::Cuda);
        EXPECT_EQ(resolveBackend("t", BackendRequest::Cuda).deviceId, usableDevices().front().id);
    }
}
