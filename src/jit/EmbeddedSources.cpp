// Hash and on-disk copy of the embedded sources; the file table itself is generated at build time
// (EmbeddedSourcesData.cpp, see cmake/EmbedSources.cmake).
#include "jit/EmbeddedSources.h"

#include <deme/Error.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <string_view>

#include "jit/KernelCache.h"

namespace deme::jit {

namespace fs = std::filesystem;

namespace {

const char* const kCall = "materializeEmbeddedSources";

// A tree left incomplete by hand (someone cleaning the cache) would give baffling compile errors.
bool treeIsComplete(const fs::path& root) {
    std::error_code ec;
    for (const EmbeddedFile& f : embeddedSources()) {
        const fs::path p = root / f.path;
        if (!fs::is_regular_file(p, ec) || fs::file_size(p, ec) != f.size) return false;
    }
    return true;
}

void writeTree(const fs::path& root) {
    for (const EmbeddedFile& f : embeddedSources()) {
        const fs::path p = root / f.path;
        std::error_code ec;
        fs::create_directories(p.parent_path(), ec);
        std::ofstream out(p, std::ios::binary);
        out.write(f.text, (std::streamsize)f.size);
        out.close();
        if (!out) throwError(kCall, "cannot write '" + p.string() + "'");
    }
}

}  // namespace

const std::string& embeddedSourcesHash() {
    static const std::string hash = [] {
        std::vector<std::string> parts;
        for (const EmbeddedFile& f : embeddedSources()) {
            parts.emplace_back(f.path);
            parts.emplace_back(f.text, f.size);
        }
        return cacheKey(parts);
    }();
    return hash;
}

std::string materializeEmbeddedSources(const std::string& cacheDirectory) {
    static std::mutex mutex;
    static std::map<std::string, std::string> materialized;  // cache directory -> include root
    std::lock_guard<std::mutex> lock(mutex);
    std::error_code ec;
    // One stat, in case the cache was cleaned while this process ran.
    if (auto it = materialized.find(cacheDirectory); it != materialized.end() && fs::is_directory(it->second, ec))
        return it->second;

    KernelCache cache(cacheDirectory);  // creates the directory, or says why it cannot
    const fs::path root = fs::path(cacheDirectory) / ("include-" + embeddedSourcesHash());
    if (fs::exists(root, ec) && !treeIsComplete(root)) fs::remove_all(root, ec);
    if (!fs::exists(root, ec)) {
        // Built aside and renamed into place whole: another process either sees the complete tree or
        // none, and if it renamed its own first, ours is redundant (the hash says they are equal).
        const fs::path temp = cache.temporaryPath("-include");
        try {
            writeTree(temp);
        } catch (...) {
            fs::remove_all(temp, ec);
            throw;
        }
        if (std::rename(temp.c_str(), root.c_str()) != 0) {
            const int err = errno;
            fs::remove_all(temp, ec);
            if (!fs::is_directory(root, ec))
                throwError(kCall,
                           "cannot move '" + temp.string() + "' to '" + root.string() + "': " + std::strerror(err));
        }
    }
    return materialized[cacheDirectory] = root.string();
}

std::string materializeEmbeddedSources() { return materializeEmbeddedSources(defaultKernelCache().directory()); }

}  // namespace deme::jit
