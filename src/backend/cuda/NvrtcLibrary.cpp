#include "backend/cuda/NvrtcLibrary.h"

#include "backend/cuda/NvrtcCompiler.h"

#include <deme/Error.h>

#include <dlfcn.h>

#include <mutex>
#include <vector>

namespace deme::cuda {

namespace {

// Where the build found NVRTC (cmake/CudaBackend.cmake), then its names on the loader's path.
std::vector<const char*> candidateNames() {
    std::vector<const char*> names;
#ifdef DEME_NVRTC_LIBRARY
    names.push_back(DEME_NVRTC_LIBRARY);
#endif
#ifdef DEME_NVRTC_SONAME
    names.push_back(DEME_NVRTC_SONAME);
#endif
    names.push_back("libnvrtc.so");
    return names;
}

struct Loaded {
    NvrtcApi api{};
    std::string error;  // why it could not be loaded; empty once loaded
    bool loaded = false;
};

template <class F>
bool resolve(void* lib, const char* name, F& f, std::string& error) {
    f = reinterpret_cast<F>(dlsym(lib, name));
    if (!f) error = std::string("NVRTC has no ") + name;
    return f != nullptr;
}

Loaded load() {
    Loaded l;
    void* lib = nullptr;
    std::string tried;
    for (const char* name : candidateNames()) {
        lib = dlopen(name, RTLD_NOW | RTLD_LOCAL);
        if (lib) break;
        const char* why = dlerror();
        tried += std::string(tried.empty() ? "" : "; ") + (why ? why : name);
    }
    if (!lib) {
        l.error = "the NVRTC library could not be loaded (" + tried + ")";
        return l;
    }
    NvrtcApi& a = l.api;
    // (The handle is kept for the process's lifetime: compiled programs may be built at any time.)
    if (resolve(lib, "nvrtcGetErrorString", a.getErrorString, l.error) &&
        resolve(lib, "nvrtcVersion", a.version, l.error) &&
        resolve(lib, "nvrtcGetNumSupportedArchs", a.getNumSupportedArchs, l.error) &&
        resolve(lib, "nvrtcGetSupportedArchs", a.getSupportedArchs, l.error) &&
        resolve(lib, "nvrtcCreateProgram", a.createProgram, l.error) &&
        resolve(lib, "nvrtcDestroyProgram", a.destroyProgram, l.error) &&
        resolve(lib, "nvrtcCompileProgram", a.compileProgram, l.error) &&
        resolve(lib, "nvrtcGetProgramLogSize", a.getProgramLogSize, l.error) &&
        resolve(lib, "nvrtcGetProgramLog", a.getProgramLog, l.error) &&
        resolve(lib, "nvrtcGetPTXSize", a.getPTXSize, l.error) && resolve(lib, "nvrtcGetPTX", a.getPTX, l.error) &&
        resolve(lib, "nvrtcGetCUBINSize", a.getCUBINSize, l.error) &&
        resolve(lib, "nvrtcGetCUBIN", a.getCUBIN, l.error))
        l.loaded = true;
    return l;
}

std::once_flag g_once;
Loaded* g_loaded = nullptr;  // made once, never freed (the functions serve until the process ends)

}  // namespace

const NvrtcApi& nvrtc(const std::string& call) {
    std::call_once(g_once, [] { g_loaded = new Loaded(load()); });
    if (!g_loaded->loaded) throwError(call, g_loaded->error);
    return g_loaded->api;
}

bool nvrtcIsLoaded() {
    void* lib = nullptr;
    for (const char* name : candidateNames())
        if ((lib = dlopen(name, RTLD_NOW | RTLD_NOLOAD)) != nullptr) break;
    if (lib) dlclose(lib);  // (RTLD_NOLOAD took a reference: given back)
    return lib != nullptr;
}

}  // namespace deme::cuda
