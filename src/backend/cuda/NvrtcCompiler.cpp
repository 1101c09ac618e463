#include "backend/cuda/NvrtcCompiler.h"

#include "jit/CompilerLog.h"

#include <deme/Error.h>

#include <cuda_runtime_api.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include "backend/cuda/Device.h"
#include "backend/cuda/NvrtcHeaders.h"
#include "backend/cuda/NvrtcLibrary.h"
#include "jit/EmbeddedSources.h"

namespace deme::cuda {

namespace {

constexpr size_t kMaxLogLines = 40;

std::string joined(const std::vector<std::string>& words) {
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : " ") + w;
    return s;
}

void checkNvrtc(nvrtcResult result, const std::string& call, const char* what) {
    if (result != NVRTC_SUCCESS) throwError(call, std::string(what) + " failed: " + nvrtc(call).getErrorString(result));
}

// Destroys the program however the scope ends.
struct ProgramHandle {
    const NvrtcApi& api;
    nvrtcProgram program = nullptr;
    ~ProgramHandle() {
        if (program) api.destroyProgram(&program);
    }
};

std::vector<int> supportedArchitectures(const std::string& call) {
    const NvrtcApi& api = nvrtc(call);
    int n = 0;
    if (api.getNumSupportedArchs(&n) != NVRTC_SUCCESS || n <= 0) return {};
    std::vector<int> archs(n);
    if (api.getSupportedArchs(archs.data()) != NVRTC_SUCCESS) return {};
    std::sort(archs.begin(), archs.end());
    return archs;
}

// The architecture for the GPU this thread uses: CUBIN for exactly it where NVRTC knows it, else
// PTX of the newest architecture NVRTC knows, which the driver compiles for the newer GPU.
std::string currentDeviceArchitecture(const std::string& call) {
    const DeviceQuery& q = queryDevices();
    if (q.usable.empty())
        throwError(call, "no GPU architecture was named and there is no usable GPU to compile for: " + q.whyNone);
    int id = 0;
    if (cudaGetDevice(&id) != cudaSuccess) {
        cudaGetLastError();
        id = q.usable.front().id;
    }
    const DeviceInfo* device = &q.usable.front();
    for (const DeviceInfo& d : q.usable)
        if (d.id == id) device = &d;
    const int cc = device->major * 10 + device->minor;
    const std::vector<int> archs = supportedArchitectures(call);
    if (archs.empty() || std::find(archs.begin(), archs.end(), cc) != archs.end()) return device->architecture();
    if (cc > archs.back()) return "compute_" + std::to_string(archs.back());
    throwError(call, "GPU " + std::to_string(device->id) + " (" + device->name + ", " + device->architecture() +
                         ") is older than any architecture NVRTC " + nvrtcVersionString() + " compiles for");
}

std::optional<std::string> readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return std::nullopt;
    return s;
}

// Runs NVRTC; fills image, log and compileSeconds.
void runNvrtc(const std::string& call, const std::string& programName, const std::string& source,
              const std::vector<std::string>& options, CudaCompileResult& result) {
    const NvrtcHeaders& headers = nvrtcHeaders();
    std::vector<const char*> contents, names;
    for (size_t i = 0; i < headers.names.size(); i++) {
        contents.push_back(headers.contents[i].c_str());
        names.push_back(headers.names[i].c_str());
    }
    const std::string text = resolveEmbeddedIncludes(source, programName);

    const auto start = std::chrono::steady_clock::now();
    const NvrtcApi& api = nvrtc(call);
    ProgramHandle prog{api};
    checkNvrtc(api.createProgram(&prog.program, text.c_str(), programName.c_str(), (int)names.size(), contents.data(),
                                 names.data()),
               call, "nvrtcCreateProgram");
    std::vector<const char*> argv;
    for (const std::string& o : options) argv.push_back(o.c_str());
    const nvrtcResult compiled = api.compileProgram(prog.program, (int)argv.size(), argv.data());

    size_t logSize = 0;
    api.getProgramLogSize(prog.program, &logSize);
    std::string log(logSize, '\0');
    if (logSize > 0) api.getProgramLog(prog.program, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    log = jit::gccStyleLocations(log);
    if (compiled != NVRTC_SUCCESS)
        throwError(call, "compiling CUDA program '" + programName + "' for " + result.architecture + " failed (NVRTC " +
                             nvrtcVersionString() + ", " + api.getErrorString(compiled) + "):\n" +
                             jit::firstLines(log, kMaxLogLines));

    size_t size = 0;
    if (result.kind == GpuImageKind::Ptx) {
        checkNvrtc(api.getPTXSize(prog.program, &size), call, "nvrtcGetPTXSize");
        result.image.assign(size, '\0');
        checkNvrtc(api.getPTX(prog.program, result.image.data()), call, "nvrtcGetPTX");
        // The size counts the terminating NUL, which std::string keeps anyway.
        while (!result.image.empty() && result.image.back() == '\0') result.image.pop_back();
    } else {
        checkNvrtc(api.getCUBINSize(prog.program, &size), call, "nvrtcGetCUBINSize");
        result.image.assign(size, '\0');
        checkNvrtc(api.getCUBIN(prog.program, result.image.data()), call, "nvrtcGetCUBIN");
    }
    result.log = log;
    result.compileSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::string nvrtcVersionString() {
    int major = 0, minor = 0;
    // (Loads the library: a compile's cache key names its version, so a cached image needs it too.)
    if (nvrtc("compiling a CUDA kernel").version(&major, &minor) != NVRTC_SUCCESS) return "unknown";
    return std::to_string(major) + "." + std::to_string(minor);
}

CudaCompileResult compileCudaSource(const std::string& call, const std::string& programName, const std::string& source,
                                    const CudaCompileOptions& options, jit::KernelCache& cache) {
    CudaCompileResult result;
    result.architecture = options.architecture.empty() ? currentDeviceArchitecture(call) : options.architecture;
    if (result.architecture.rfind("sm_", 0) == 0) {
        result.kind = GpuImageKind::Cubin;
    } else if (result.architecture.rfind("compute_", 0) == 0) {
        result.kind = GpuImageKind::Ptx;
    } else {
        throwError(call, "unknown GPU architecture '" + result.architecture +
                             "': name a real one as sm_XX (CUBIN) or a virtual one as compute_XX (PTX)");
    }

    std::vector<std::string> nvrtcOptions = nvrtcBaseOptions(result.architecture);
    for (const std::string& d : options.defines) nvrtcOptions.push_back("-D" + d);
    // A diagnostic switch: macros for every kernel compiled, space-separated (DEME_CUDA_DEFINES="A=1 B"),
    // so that one binary can time variants of a kernel (tests/gpu/run.sh smallab); in the cache key.
    if (const char* extra = std::getenv("DEME_CUDA_DEFINES")) {
        std::istringstream words(extra);
        for (std::string d; words >> d;) nvrtcOptions.push_back("-D" + d);
    }
    nvrtcOptions.insert(nvrtcOptions.end(), options.extraOptions.begin(), options.extraOptions.end());

    const std::string suffix = result.kind == GpuImageKind::Ptx ? ".ptx" : ".cubin";
    result.key = jit::cacheKey({"nvrtc-image-v1", programName, source, jit::embeddedSourcesHash(), nvrtcVersionString(),
                                result.architecture, joined(nvrtcOptions)});
    if (auto path = cache.lookup(result.key, suffix)) {
        // A file deleted or unreadable since the lookup (someone cleaning the cache) is compiled anew.
        if (auto image = readFile(*path); image && !image->empty()) {
            result.image = std::move(*image);
            result.cacheHit = true;
            return result;
        }
    }

    runNvrtc(call, programName, source, nvrtcOptions, result);
    cache.publish(result.key, suffix, [&](const std::string& tempPath) {
        std::ofstream out(tempPath, std::ios::binary);
        out.write(result.image.data(), (std::streamsize)result.image.size());
        out.close();
        if (!out) throwError(call, "cannot write the compiled GPU image to '" + tempPath + "'");
    });
    return result;
}

}  // namespace deme::cuda
