#include "jit/KernelCache.h"

#include <deme/Error.h>

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <thread>

namespace deme::jit {

namespace fs = std::filesystem;

namespace {

// FNV-1a with the 128-bit parameters (offset basis and prime from the FNV reference).
class Fnv1a128 {
  public:
    void bytes(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; i++) {
            h_ ^= p[i];
            h_ *= kPrime;
        }
    }
    // Fixed-width little-endian, so that the key does not depend on the host's byte order.
    void length(uint64_t n) {
        unsigned char le[8];
        for (int i = 0; i < 8; i++) le[i] = (unsigned char)(n >> (8 * i));
        bytes(le, sizeof le);
    }
    std::string hex() const {
        static const char digits[] = "0123456789abcdef";
        std::string s(32, '0');
        unsigned __int128 v = h_;
        for (int i = 31; i >= 0; i--, v >>= 4) s[i] = digits[(unsigned)(v & 0xf)];
        return s;
    }

  private:
    static constexpr unsigned __int128 kPrime = ((unsigned __int128)1 << 88) + 0x13b;
    unsigned __int128 h_ = ((unsigned __int128)0x6c62272e07bb0142ULL << 64) | 0x62b821756295c58dULL;
};

template <class Range>
std::string hashParts(const Range& parts) {
    Fnv1a128 h;
    h.length(parts.size());
    for (const auto& part : parts) {
        const std::string_view s(part);
        h.length(s.size());
        h.bytes(s.data(), s.size());
    }
    return h.hex();
}

bool isSet(const char* v) { return v && *v; }

}  // namespace

std::string cacheKey(std::initializer_list<std::string_view> parts) { return hashParts(parts); }
std::string cacheKey(const std::vector<std::string>& parts) { return hashParts(parts); }

std::string cacheDirectoryFor(const CacheDirectoryEnvironment& env) {
    if (isSet(env.demeCacheDir)) return env.demeCacheDir;
    if (isSet(env.xdgCacheHome)) return (fs::path(env.xdgCacheHome) / "deme").string();
    if (isSet(env.home)) return (fs::path(env.home) / ".cache" / "deme").string();
    // Per user, so that one user's files never block another's.
    return "/tmp/deme-cache-" + std::to_string(getuid());
}

std::string defaultCacheDirectory() {
    return cacheDirectoryFor({std::getenv("DEME_CACHE_DIR"), std::getenv("XDG_CACHE_HOME"), std::getenv("HOME")});
}

KernelCache::KernelCache(std::string directory) : directory_(std::move(directory)) {
    std::error_code ec;
    fs::create_directories(directory_, ec);
    if (ec || !fs::is_directory(directory_))
        throwError("KernelCache", "cannot create the cache directory '" + directory_ + "'" +
                                      (ec ? ": " + ec.message() : std::string()) +
                                      " (set DEME_CACHE_DIR to a writable directory)");
}

std::string KernelCache::artifactPath(const std::string& key, const std::string& suffix) const {
    return (fs::path(directory_) / (key + suffix)).string();
}

std::optional<std::string> KernelCache::lookup(const std::string& key, const std::string& suffix) {
    std::string path = artifactPath(key, suffix);
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) {
        hits_++;
        return path;
    }
    misses_++;
    return std::nullopt;
}

std::string KernelCache::temporaryPath(const std::string& suffix) const {
    static std::atomic<uint64_t> counter{0};
    const size_t thread = std::hash<std::thread::id>{}(std::this_thread::get_id());
    const std::string name =
        ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(thread) + "-" + std::to_string(counter++) + suffix;
    return (fs::path(directory_) / name).string();
}

std::string KernelCache::publish(const std::string& key, const std::string& suffix,
                                 const std::function<void(const std::string& tempPath)>& producer) {
    const std::string temp = temporaryPath(suffix);
    const std::string final = artifactPath(key, suffix);
    std::error_code ec;
    // The directory may have been removed since (a user clearing the cache while a program runs).
    fs::create_directories(directory_, ec);
    try {
        producer(temp);
    } catch (...) {
        fs::remove(temp, ec);
        throw;
    }
    if (!fs::is_regular_file(temp, ec))
        throwError("KernelCache::publish", "the producer of '" + final + "' did not write '" + temp + "'");
    if (fs::exists(final, ec)) {
        // Same key, same inputs: the artifact already there is as good as ours.
        fs::remove(temp, ec);
        return final;
    }
    // rename() is atomic within one file system: readers see either no file or the whole file. Should
    // another producer rename between the check above and here, its equal file is replaced whole.
    if (std::rename(temp.c_str(), final.c_str()) != 0) {
        const int err = errno;
        fs::remove(temp, ec);
        throwError("KernelCache::publish", "cannot move '" + temp + "' to '" + final + "': " + std::strerror(err));
    }
    published_++;
    return final;
}

CacheStats KernelCache::stats() const {
    CacheStats s;
    s.hits = hits_.load();
    s.misses = misses_.load();
    s.published = published_.load();
    return s;
}

KernelCache& defaultKernelCache() {
    static KernelCache cache;
    return cache;
}

}  // namespace deme::jit
