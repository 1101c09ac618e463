// The text of the headers that run-time compiled code includes, embedded into the library at build
// time (cmake/EmbedSources.cmake lists them). Run-time compiled code thus sees the very physics and
// state code the library was built from, wherever the library is installed.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace deme::jit {

struct EmbeddedFile {
    // Relative to an include root, as the sources' own #include lines expect: include/deme/X.h is
    // "deme/X.h", src/physics/Y.h is "physics/Y.h".
    const char* path;
    const char* text;  // NUL-terminated; `size` bytes before the NUL
    size_t size;
};

// Sorted by path.
const std::vector<EmbeddedFile>& embeddedSources();

// Hash of every embedded path and text; part of the cache key of anything compiled against them.
const std::string& embeddedSourcesHash();

// Writes the embedded files under <cacheDirectory>/include-<hash>/ (once per process and directory;
// atomically, so concurrent writers never expose a partial tree) and returns that directory, for a
// compiler's -I.
std::string materializeEmbeddedSources(const std::string& cacheDirectory);
// The same in defaultKernelCache()'s directory.
std::string materializeEmbeddedSources();

}  // namespace deme::jit
