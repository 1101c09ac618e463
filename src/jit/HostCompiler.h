// Compiles a C++ translation unit into a shared object with the host C++ compiler and loads it.
// The result is cached on disk (KernelCache), keyed by everything that affects the machine code, so a
// program run again with the same code loads it without compiling.
#pragma once

#include <string>
#include <vector>

#include "jit/KernelCache.h"

namespace deme::jit {

// A shared object opened with dlopen (RTLD_NOW | RTLD_LOCAL), closed with its last owner.
class CompiledModule {
  public:
    CompiledModule() = default;
    // Throws deme::Error naming `call` if the object cannot be loaded.
    CompiledModule(const std::string& call, const std::string& path);
    ~CompiledModule();
    CompiledModule(CompiledModule&& other) noexcept;
    CompiledModule& operator=(CompiledModule&& other) noexcept;
    CompiledModule(const CompiledModule&) = delete;
    CompiledModule& operator=(const CompiledModule&) = delete;

    // The address of an exported symbol (declare it extern "C"); throws deme::Error, naming the call
    // that built the module, if there is none.
    void* symbol(const char* name) const;
    // symbol() cast to a function type, e.g. module.function<int(int, int)>("add").
    template <class Signature>
    Signature* function(const char* name) const {
        return reinterpret_cast<Signature*>(symbol(name));
    }

    bool loaded() const { return handle_ != nullptr; }
    const std::string& path() const { return path_; }

  private:
    void* handle_ = nullptr;
    std::string call_;
    std::string path_;
};

struct HostCompileResult {
    CompiledModule module;
    bool cacheHit = false;
    double compileSeconds = 0;  // wall time spent in the compiler; 0 on a cache hit
    std::string key;            // the cache key of the shared object
};

// The compiler: the words of DEME_CXX if set (so a launcher such as "ccache g++" works), else the
// compiler the library was built with.
std::vector<std::string> hostCompilerCommand();
// Flags for every compilation, besides -I<embedded sources> and -o: -std=c++17 -O3 -fPIC -shared
// -fopenmp and the library's floating-point options (-fno-math-errno), plus -march=native and -DNDEBUG
// when the library was built with them, so that run-time code computes exactly what the same code
// built into the library would.
std::vector<std::string> hostCompilerFlags();

// Compiles `source`, which may include the embedded sources (materializeEmbeddedSources()) as the
// library's own code does, e.g. "physics/Quaternion.h" or <deme/VectorTypes.h>, and loads the result.
// `extraFlags` are added to the command line and to the key. A compiler error throws deme::Error:
// "<call>: " + a short header + the compiler's first lines of output, which name the code's own file
// and line where the source marks them with #line.
HostCompileResult compileHostModule(const std::string& call, const std::string& source,
                                    KernelCache& cache = defaultKernelCache(),
                                    const std::vector<std::string>& extraFlags = {});

}  // namespace deme::jit
