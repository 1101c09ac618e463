// A directory of artifacts compiled at run time (shared objects, PTX, ...), named by a hash of
// everything that went into them. Several threads or processes may share one directory: an artifact
// appears under its final name only once it is complete, so no reader ever sees a half-written file.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace deme::jit {

// 128-bit FNV-1a over the parts, as 32 hex digits. Each part's length is hashed before its bytes,
// so ("ab", "c") and ("a", "bc") give different keys.
std::string cacheKey(std::initializer_list<std::string_view> parts);
std::string cacheKey(const std::vector<std::string>& parts);

// The environment variables that choose the cache directory; null or empty means unset.
struct CacheDirectoryEnvironment {
    const char* demeCacheDir = nullptr;  // DEME_CACHE_DIR
    const char* xdgCacheHome = nullptr;  // XDG_CACHE_HOME
    const char* home = nullptr;          // HOME
};
// DEME_CACHE_DIR, else $XDG_CACHE_HOME/deme, else $HOME/.cache/deme, else /tmp/deme-cache-<uid>.
std::string cacheDirectoryFor(const CacheDirectoryEnvironment& env);
// cacheDirectoryFor() with this process's environment. Does not create the directory.
std::string defaultCacheDirectory();

struct CacheStats {
    uint64_t hits = 0;       // lookups that found the artifact
    uint64_t misses = 0;     // lookups that did not
    uint64_t published = 0;  // artifacts this object produced and moved into place
};

class KernelCache {
  public:
    // Creates the directory (and its parents) if missing; throws deme::Error if it cannot.
    explicit KernelCache(std::string directory = defaultCacheDirectory());

    const std::string& directory() const { return directory_; }

    // Where the artifact <key><suffix> lives (whether or not it exists yet).
    std::string artifactPath(const std::string& key, const std::string& suffix) const;

    // The artifact's path if it exists. Counts a hit or a miss.
    std::optional<std::string> lookup(const std::string& key, const std::string& suffix);

    // Runs producer(tempPath), which must write the artifact to tempPath (a fresh name in this
    // directory), then renames it to the final name and returns that. If another producer got there
    // first, the temporary file is deleted and the existing artifact kept. If the producer throws, the
    // temporary file is deleted and the exception propagates.
    std::string publish(const std::string& key, const std::string& suffix,
                        const std::function<void(const std::string& tempPath)>& producer);

    // A name in this directory that no other thread or process will use: hidden, made of pid, thread
    // and a per-process counter, ending in `suffix` (compilers pick the file type from it).
    std::string temporaryPath(const std::string& suffix) const;

    CacheStats stats() const;

  private:
    std::string directory_;
    std::atomic<uint64_t> hits_{0}, misses_{0}, published_{0};
};

// The cache in defaultCacheDirectory(), created on first use.
KernelCache& defaultKernelCache();

}  // namespace deme::jit
