// The contact force model on the CPU backend: its layout (names for the host-side wildcard API) and
// its force pass, built into the library or loaded from a module compiled at run time.
#pragma once

#include <memory>

#include "backend/cpu/ForcePass.h"
#include "forcemodel/ModelLayout.h"

namespace deme {

namespace jit {
class CompiledModule;
}

struct CpuForceModel {
    ModelLayout layout;
    ForcePassFunction pass = nullptr;
    std::shared_ptr<jit::CompiledModule> module;  // keeps a run-time compiled pass loaded
    bool cacheHit = false;                        // a custom model was found compiled in the cache
    double compileSeconds = 0.0;                  // time in the compiler (0 on a cache hit)
};

// The built-in pass for a built-in model; for a custom model, generates its source, compiles it (or
// finds it in the kernel cache) and loads its pass. A compile error throws deme::Error naming `call`
// and quoting the compiler, whose messages point into the user's code.
CpuForceModel loadCpuForceModel(const ModelLayout& layout, const char* call);

}  // namespace deme
