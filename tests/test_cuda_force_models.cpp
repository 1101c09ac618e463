// Force models on the CUDA backend, checked without a GPU (they run in CI): the kernels NVRTC
// compiles for them reach PTX for sm_90 (compute_90), a custom model's generated kernel included, and
// an error in a model's code is reported at the line of that code. The runs on a GPU are the cuda
// instances of the force model tests (test_force_models*.cpp). Skipped in a build without CUDA.
#include <gtest/gtest.h>

#include <deme/Error.h>

#include <algorithm>
#include <optional>
#include <string>

#include "BondedCompression.h"
#include "ForceModelTestUtil.h"
#include "ScratchDirTest.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "forcemodel/CudaCodeGen.h"

using namespace deme;
using namespace deme::cuda;

namespace {

ModelLayout customLayout(const std::string& source) {
    ModelLayout L;
    L.kind = DEMForceModel::Kind::CUSTOM;
    L.source = source;
    L.origin = "force_model";
    return L;
}

// Each test gets its own kernel cache, so every compile here is a real one.
class CudaForceModelNvrtc : public deme_test::ScratchDirTest {
  protected:
    void SetUp() override {
        if (!cudaBackendBuilt()) GTEST_SKIP() << "the library was built without the CUDA backend";
        ScratchDirTest::SetUp();
        cache.emplace(dir.string());
    }
    // What DeviceForceModel::load does for a custom model, for compute_90 PTX.
    CudaCompileResult compileModel(const ModelLayout& L) {
        CudaCompileOptions options;
        options.architecture = "compute_90";
        return compileCudaSource("Initialize (contact force model)", kGeneratedForceKernelProgram,
                                 generateCudaForceModelSource(L), options, *cache);
    }
    CudaCompileResult compileEmbedded(const std::string& path) {
        CudaCompileOptions options;
        options.architecture = "compute_90";
        return compileCudaSource("test", path, deme_test::embeddedText(path), options, *cache);
    }
    void expectUserKernel(const CudaCompileResult& r) {
        EXPECT_EQ(r.kind, GpuImageKind::Ptx);
        EXPECT_NE(r.image.find(".target sm_90"), std::string::npos);
        EXPECT_NE(r.image.find(".entry " + std::string(kGeneratedForceKernelSymbol) + "("), std::string::npos);
        // and the pass of scenes without meshes
        EXPECT_NE(r.image.find(".entry " + std::string(kGeneratedNoMeshForceKernelSymbol) + "("), std::string::npos);
    }
    std::optional<jit::KernelCache> cache;
};

}  // namespace

// Owner wildcards, read per owner.
TEST_F(CudaForceModelNvrtc, CoulombModelCompiles) {
    ModelLayout L = customLayout(deme_test::kElectrostatic);
    L.ownerWildcards = {"Q"};
    expectUserKernel(compileModel(L));
}

// Material properties per pair, the derived tables, deme::PI.
TEST_F(CudaForceModelNvrtc, DmtModelCompiles) {
    ModelLayout L = customLayout(deme_test::kDMT);
    L.materialProps = {"E", "nu", "CoR"};
    L.pairProps = {"W"};  // a property read per pair is in pairProps only
    expectUserKernel(compileModel(L));
}

// Contact wildcards and an owner wildcard the model writes.
TEST_F(CudaForceModelNvrtc, ContactAgeModelCompiles) {
    ModelLayout L = customLayout(deme_test::kAgeCounter);
    L.contactWildcards = {"age"};
    L.ownerWildcards = {"ageSeen"};
    expectUserKernel(compileModel(L));
}

// The default model's text, every input and table of it; and the bonded model, which writes
// `persistent` and reads geometry wildcards.
TEST_F(CudaForceModelNvrtc, DefaultAndBondedModelsCompile) {
    ModelLayout L = customLayout(deme_test::hertzMindlinSnippet());
    L.materialProps = {"E", "nu"};  // a property read per pair is in pairProps only
    L.pairProps = {"CoR", "mu", "Crr"};
    L.contactWildcards = {"delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time"};
    expectUserKernel(compileModel(L));
    ModelLayout B = customLayout(bonded_demo::kBondedModel);
    B.materialProps = {"kb", "cb"};
    B.contactWildcards = {"bonded", "overlap0"};
    B.geometryWildcards = {"strength"};
    expectUserKernel(compileModel(B));
}

// The built-in models' force passes are kernels of the dynamics module: no compile of their own.
TEST_F(CudaForceModelNvrtc, BuiltInForcePassesAreInTheDynamicsModule) {
    const CudaCompileResult r = compileEmbedded("backend/cuda/kernels/Dynamics.cu");
    EXPECT_NE(r.image.find(".entry deme_force_pass_frictional_hertz"), std::string::npos);
    EXPECT_NE(r.image.find(".entry deme_force_pass_frictionless_hertz"), std::string::npos);
    const CudaCompileResult p = compileEmbedded("backend/cuda/kernels/HistoryMapping.cu");
    for (const char* k : {"deme_persistent_missing", "deme_persistent_merge", "deme_map_history"})
        EXPECT_NE(p.image.find(".entry " + std::string(k)), std::string::npos) << k;
}

// On sm_90 the passes add the owners' loads as vector reductions (kernels/ForcePassKernel.cuh,
// DEME_VECTOR_ATOMICS): red.v4 where a load shares a 16-byte chunk with one neighbour's float, red.v2
// elsewhere; a custom model's pass instantiates the same code. (ptxas accepts them for sm_90: the
// GPU suite runs them.)
TEST_F(CudaForceModelNvrtc, PassesAddTheOwnersLoadsAsVectorReductions) {
    const CudaCompileResult r = compileEmbedded("backend/cuda/kernels/Dynamics.cu");
    EXPECT_NE(r.image.find("red.global.add.v4.f32"), std::string::npos);
    EXPECT_NE(r.image.find("red.global.add.v2.f32"), std::string::npos);
    ModelLayout L = customLayout(deme_test::kElectrostatic);
    L.ownerWildcards = {"Q"};
    const CudaCompileResult m = compileModel(L);
    EXPECT_NE(m.image.find("red.global.add.v4.f32"), std::string::npos);
}

// An error in the model's code: a deme::Error naming the call and quoting NVRTC at the code's own
// line (the generated prologue does not count), for a syntax error and for an unknown name.
TEST_F(CudaForceModelNvrtc, ErrorsNameTheSnippetLine) {
    const std::string syntax = deme_test::demeErrorMessage(
        [&] { compileModel(customLayout("const float k = 2.f;\nforce += k * B2A +;\n")); });
    EXPECT_EQ(syntax.rfind("Initialize (contact force model): ", 0), 0u) << syntax;
    EXPECT_NE(syntax.find("force_model:2: error"), std::string::npos) << syntax;
    const std::string unknown = deme_test::demeErrorMessage(
        [&] { compileModel(customLayout("const float k = 2.f;\n\nforce += stifness * B2A;\n")); });
    EXPECT_NE(unknown.find("force_model:3: error"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("stifness"), std::string::npos) << unknown;
}

// Numbering returns to the generated text after the model's code, so a message about generated code
// names the generated file and a line that exists in it.
TEST_F(CudaForceModelNvrtc, LineNumberingResumesAfterTheSnippet) {
    const std::string src = generateCudaForceModelSource(customLayout("force += B2A;\n"));
    const size_t at = src.find("#line ", src.find("#line 1 \"force_model\"") + 1);
    ASSERT_NE(at, std::string::npos);
    const size_t lineOfDirective = (size_t)std::count(src.begin(), src.begin() + (ptrdiff_t)at, '\n') + 1;
    EXPECT_EQ(src.substr(at, src.find('\n', at) - at),
              "#line " + std::to_string(lineOfDirective + 1) + " \"" + kGeneratedForceKernelProgram + "\"");
}
