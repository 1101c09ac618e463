// MODEL-COMPILE: how long Initialize() takes to compile a custom contact force model (the default
// Hertz-Mindlin model written out as a snippet), with an empty kernel cache ("cold"), with the model
// in the cache from earlier in the same program ("cached"), and in a new program run
// ("cached-new-process", this program run again). model_s is the Initialize time minus that of the same
// scene with the built-in model (fastest of 3 cold, 5 other runs). One JSON line per case.
// On the CUDA backend Initialize compiles the snippet twice, for the host and with NVRTC for the GPU;
// there "cold" means the model alone is not cached (the library's kernels are, as after any earlier
// run), so model_s is what a new model costs.
//   usage: model_compile [cache_dir|-] [cpu|cuda]   (default: a fresh directory under /tmp, removed at
//   the end; the CPU backend)
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <deme/deme.h>

#include "BenchUtil.h"
#include "HertzMindlinSnippet.h"

using namespace deme;
using namespace deme_bench;
namespace fs = std::filesystem;

namespace {

// Seconds Initialize() takes on a small bed, with the built-in model or the snippet.
std::string g_backend = "cpu";

double initializeSeconds(bool custom) {
    DEMSolver sim;
    sim.SetVerbosity("ERROR");
    sim.SetBackend(g_backend);
    auto mat = sim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.01}});
    if (custom) useHertzMindlinSnippet(sim);
    sim.InstructBoxDomainDimension(0.1f, 0.1f, 0.1f);
    sim.InstructBoxDomainBoundingBC("all", mat);
    sim.AddClumps(sim.LoadSphereType(1e-5f, 0.002f, mat),
                  HCPSampler(0.0045f).SampleBox(make_float3(0, 0, 0), make_float3(0.04f, 0.04f, 0.04f)));
    sim.SetInitTimeStep(1e-5);
    const double t0 = seconds();
    sim.Initialize();
    return seconds() - t0;
}

// The fastest of n runs: other processes on the machine can only add time.
template <class F>
double fastest(int n, F f) {
    double t = f();
    for (int i = 1; i < n; i++) t = std::min(t, f());
    return t;
}

void report(const std::string& variant, double custom, double builtIn) {
    JsonLine j;
    j.add("case", "MODEL-COMPILE")
        .add("variant", variant)
        .add("backend", g_backend)
        .add("device", cpuName() + " x " + std::to_string(std::thread::hardware_concurrency()) + " threads")
        .add("model", "Hertz-Mindlin as a snippet")
        .add("initialize_s", custom)
        .add("builtin_initialize_s", builtIn)
        .add("model_s", custom - builtIn);
    std::cout << j.str() << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
    const bool child = argc > 2 && std::string(argv[1]) == "--cached-run";
    if (argc > (child ? 3 : 2)) g_backend = argv[child ? 3 : 2];
    const bool ownDir = argc < 2 || std::string(argv[1]) == "-";
    const fs::path dir = child    ? fs::path(argv[2])
                         : ownDir ? fs::temp_directory_path() / ("deme_model_compile_" + std::to_string(getpid()))
                                  : fs::path(argv[1]);
    // The kernel cache directory is read on first use, so it is set before any solver exists.
    setenv("DEME_CACHE_DIR", dir.c_str(), 1);
    if (child) {
        // The first custom Initialize of a new process: a cache hit, plus what a process does once
        // (asking the compiler for its version, part of the key).
        const double custom = initializeSeconds(true);
        report("cached-new-process", custom, fastest(5, [] { return initializeSeconds(false); }));
        return 0;
    }
    const double builtIn = fastest(5, [] { return initializeSeconds(false); });
    std::error_code ec;
    // Cold: nothing compiled yet, not even the embedded headers written out.
    const double cold = fastest(3, [&] {
        fs::remove_all(dir, ec);
        if (g_backend == "cuda") initializeSeconds(false);  // the library's kernels, cached
        return initializeSeconds(true);
    });
    report("cold", cold, builtIn);
    report("cached", fastest(5, [] { return initializeSeconds(true); }), builtIn);
    std::cout.flush();
    const std::string again =
        "\"" + std::string(argv[0]) + "\" --cached-run \"" + dir.string() + "\" " + g_backend;
    const int rc = std::system(again.c_str());
    if (ownDir) fs::remove_all(dir, ec);
    return rc == 0 ? 0 : 1;
}
