#include "backend/cuda/EmbeddedKernel.h"

#include <map>
#include <mutex>

#include <deme/Error.h>

#include "jit/EmbeddedSources.h"

namespace deme::cuda {

const std::string& embeddedKernelText(const std::string& path) {
    // Entries are never removed, so a reference stays valid after the lock is released.
    static std::mutex mutex;
    static std::map<std::string, std::string> texts;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = texts.find(path);
    if (it != texts.end()) return it->second;
    for (const jit::EmbeddedFile& f : jit::embeddedSources())
        if (path == f.path) return texts[path] = std::string(f.text, f.size);
    throwError("Initialize", "kernel source " + path + " is not embedded in this build");
}

}  // namespace deme::cuda
