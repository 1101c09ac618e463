// NVRTC-COMPILE: the GPU half of a custom force model's compile, measured without a GPU. At
// Initialize on the CUDA backend the generated force kernel (the default Hertz-Mindlin model written
// as a snippet, as in model_compile) is compiled by NVRTC for the GPU found: CUBIN for sm_90 on an
// H100/H200. Reported cold (empty kernel cache) and cached (found in the cache), and, for scale, the
// library's own Dynamics.cu, which a first run on a machine compiles once. NVRTC runs on the host
// CPU, so the figure is this machine's, whether or not it has a GPU. One JSON line per case.
//   usage: nvrtc_compile [architecture]   (default sm_90)
#include <unistd.h>

#include <filesystem>
#include <iostream>

#include <deme/Error.h>

#include "BenchUtil.h"
#include "HertzMindlinSnippet.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/EmbeddedKernel.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "forcemodel/CudaCodeGen.h"

using namespace deme;
using namespace deme::cuda;
namespace fs = std::filesystem;

namespace {

// The layout model_compile's snippet declares (bench/model_compile.cpp).
ModelLayout hertzMindlinLayout() {
    ModelLayout L;
    L.kind = DEMForceModel::Kind::CUSTOM;
    L.source = deme_bench::hertzMindlinSnippet();
    L.origin = "force_model";
    L.materialProps = {"E", "nu"};  // the pairwise ones are read per pair only (resolveModelLayout)
    L.pairProps = {"CoR", "mu", "Crr"};
    L.contactWildcards = {"delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time"};
    return L;
}

void report(const std::string& what, const std::string& variant, const std::string& arch,
            const CudaCompileResult& r, double wall) {
    deme_bench::JsonLine j;
    j.add("case", "NVRTC-COMPILE")
        .add("source", what)
        .add("variant", variant)
        .add("architecture", arch)
        .add("nvrtc", nvrtcVersionString())
        .add("device", deme_bench::cpuName() + " x " + std::to_string(std::thread::hardware_concurrency()) + " threads")
        .add("cache_hit", r.cacheHit ? "yes" : "no")
        .add("seconds", wall);
    std::cout << j.str() << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
    if (!cudaBackendBuilt()) {
        std::cerr << "nvrtc_compile: this build has no CUDA backend\n";
        return 2;
    }
    const std::string arch = argc > 1 ? argv[1] : "sm_90";
    const fs::path dir = fs::temp_directory_path() / ("deme_nvrtc_compile_" + std::to_string(getpid()));
    jit::KernelCache cache(dir.string());
    CudaCompileOptions opt;
    opt.architecture = arch;
    const std::string model = generateCudaForceModelSource(hertzMindlinLayout());
    const std::string dynPath = "backend/cuda/kernels/Dynamics.cu";
    for (const char* variant : {"cold", "cached"}) {
        double t0 = deme_bench::seconds();
        CudaCompileResult r = compileCudaSource("bench", kGeneratedForceKernelProgram, model, opt, cache);
        report("custom force model (Hertz-Mindlin snippet)", variant, arch, r, deme_bench::seconds() - t0);
        t0 = deme_bench::seconds();
        r = compileCudaSource("bench", dynPath, embeddedKernelText(dynPath), opt, cache);
        report("library Dynamics.cu", variant, arch, r, deme_bench::seconds() - t0);
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
    return 0;
}
