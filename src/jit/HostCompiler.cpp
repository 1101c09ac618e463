#include "jit/HostCompiler.h"

#include "jit/CompilerLog.h"

#include <deme/Error.h>

#include <dlfcn.h>
#include <sys/utsname.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "jit/EmbeddedSources.h"
#include "jit/Subprocess.h"

// Set by CMakeLists.txt: the compiler the library was built with, and whether with -march=native.
#ifndef DEME_JIT_CXX
#define DEME_JIT_CXX "c++"
#endif
// The library's floating-point options (CMakeLists.txt: DEME_FP_OPTIONS), space-separated.
#ifndef DEME_JIT_FP_OPTIONS
#define DEME_JIT_FP_OPTIONS ""
#endif

namespace deme::jit {

namespace {

constexpr size_t kMaxErrorLines = 40;

std::string joined(const std::vector<std::string>& words) {
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : " ") + w;
    return s;
}

// First line of `<compiler> --version`, once per compiler command.
std::string compilerVersion(const std::string& call, const std::vector<std::string>& command) {
    static std::mutex mutex;
    static std::map<std::vector<std::string>, std::string> versions;
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = versions.find(command); it != versions.end()) return it->second;
    std::vector<std::string> argv = command;
    argv.push_back("--version");
    ProcessResult r;
    try {
        r = runCapturingOutput(call, argv);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + " (set DEME_CXX to a working C++ compiler)");
    }
    if (!r.succeeded())
        throwError(call, "the C++ compiler '" + joined(command) + "' does not answer --version:\n" + r.output +
                             "(set DEME_CXX to a working C++ compiler)");
    return versions[command] = r.output.substr(0, r.output.find('\n'));
}

// The machine the code is built for. With -march=native that includes the CPU model and features:
// a cache directory shared between machines (a network home) must not hand one CPU's code to another.
const std::string& targetArchitecture() {
    static const std::string arch = [] {
        utsname u{};
        std::string s = uname(&u) == 0 ? u.machine : "unknown";
#ifdef DEME_JIT_NATIVE_ARCH
        std::ifstream cpuinfo("/proc/cpuinfo");
        bool model = false, flags = false;
        for (std::string line; std::getline(cpuinfo, line) && !(model && flags);) {
            const bool isModel = line.rfind("model name", 0) == 0, isFlags = line.rfind("flags", 0) == 0;
            if ((isModel && !model) || (isFlags && !flags)) s += "\n" + line;
            model |= isModel;
            flags |= isFlags;
        }
#endif
        return s;
    }();
    return arch;
}

// Deletes a file when the scope ends, however it ends.
struct RemoveOnExit {
    std::string path;
    ~RemoveOnExit() {
        std::error_code ec;
        std::filesystem::remove(path, ec);
    }
};

}  // namespace

// ---- CompiledModule

CompiledModule::CompiledModule(const std::string& call, const std::string& path) : call_(call), path_(path) {
    handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle_) {
        const char* why = dlerror();
        throwError(call, "cannot load the compiled module '" + path + "': " + (why ? why : "unknown reason"));
    }
}

CompiledModule::~CompiledModule() {
    if (handle_) dlclose(handle_);
}

CompiledModule::CompiledModule(CompiledModule&& other) noexcept
    : handle_(other.handle_), call_(std::move(other.call_)), path_(std::move(other.path_)) {
    other.handle_ = nullptr;
}

CompiledModule& CompiledModule::operator=(CompiledModule&& other) noexcept {
    if (this != &other) {
        if (handle_) dlclose(handle_);
        handle_ = other.handle_;
        call_ = std::move(other.call_);
        path_ = std::move(other.path_);
        other.handle_ = nullptr;
    }
    return *this;
}

void* CompiledModule::symbol(const char* name) const {
    if (!handle_) throwError(call_.empty() ? "CompiledModule::symbol" : call_, "no module is loaded");
    dlerror();  // clear any earlier error, so that the one read below is this lookup's
    void* p = dlsym(handle_, name);
    if (const char* why = dlerror())
        throwError(call_, "the compiled module has no symbol '" + std::string(name) + "' (" + why + ")");
    return p;
}

// ---- compiler and flags

std::vector<std::string> hostCompilerCommand() {
    std::vector<std::string> words;
    if (const char* env = std::getenv("DEME_CXX")) {
        std::istringstream in(env);
        for (std::string w; in >> w;) words.push_back(w);
    }
    if (words.empty()) words.push_back(DEME_JIT_CXX);
    return words;
}

std::vector<std::string> hostCompilerFlags() {
    // The library's own -std, optimisation, floating-point options (-fno-math-errno) and -march, and
    // no fast-math: the compiler then makes the same floating-point choices (e.g. GCC contracts a*b+c
    // into fused multiply-adds where -march allows, as it does in the library), so run-time code
    // rounds as built-in code does.
    std::vector<std::string> flags = {"-std=c++17", "-O3", "-fPIC", "-shared", "-fopenmp"};
    std::istringstream fpOptions(DEME_JIT_FP_OPTIONS);
    for (std::string w; fpOptions >> w;) flags.push_back(w);
#ifdef DEME_JIT_NATIVE_ARCH
    flags.push_back("-march=native");
#endif
#ifdef NDEBUG
    flags.push_back("-DNDEBUG");
#endif
    return flags;
}

// ---- compile and load

HostCompileResult compileHostModule(const std::string& call, const std::string& source, KernelCache& cache,
                                    const std::vector<std::string>& extraFlags) {
    const std::vector<std::string> command = hostCompilerCommand();
    const std::vector<std::string> flags = hostCompilerFlags();
    // The include directory's path is left out of the key (its name holds the embedded hash, which is
    // in), and so is the launcher: "ccache g++" and "g++" make the same code.
    HostCompileResult result;
    result.key = cacheKey({"host-shared-object-v1", source, compilerVersion(call, command), joined(flags),
                           joined(extraFlags), targetArchitecture(), embeddedSourcesHash()});

    if (auto path = cache.lookup(result.key, ".so")) {
        result.module = CompiledModule(call, *path);
        result.cacheHit = true;
        return result;
    }

    const std::string includeDir = materializeEmbeddedSources(cache.directory());
    const RemoveOnExit sourceFile{cache.temporaryPath(".cpp")};
    {
        std::ofstream out(sourceFile.path, std::ios::binary);
        out << source;
        out.close();
        if (!out) throwError(call, "cannot write '" + sourceFile.path + "' for the C++ compiler");
    }
    const std::string path = cache.publish(result.key, ".so", [&](const std::string& tempPath) {
        std::vector<std::string> argv = command;
        argv.insert(argv.end(), flags.begin(), flags.end());
        argv.insert(argv.end(), extraFlags.begin(), extraFlags.end());
        argv.insert(argv.end(), {"-I" + includeDir, sourceFile.path, "-o", tempPath});
        const auto start = std::chrono::steady_clock::now();
        const ProcessResult r = runCapturingOutput(call, argv);
        result.compileSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!r.succeeded()) {
            const std::string how = r.signal ? "was killed by signal " + std::to_string(r.signal)
                                             : "exited with status " + std::to_string(r.exitCode);
            throwError(call, "compiling run-time generated code failed (" + joined(command) + " " + how + "):\n" +
                                 firstLines(r.output, kMaxErrorLines));
        }
    });
    result.module = CompiledModule(call, path);
    return result;
}

}  // namespace deme::jit
