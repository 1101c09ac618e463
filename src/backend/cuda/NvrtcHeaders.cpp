#include "backend/cuda/NvrtcHeaders.h"

#include <filesystem>
#include <set>

#include "jit/EmbeddedSources.h"

namespace deme::cuda {

namespace {

const std::set<std::string>& embeddedPaths() {
    static const std::set<std::string> paths = [] {
        std::set<std::string> s;
        for (const jit::EmbeddedFile& f : jit::embeddedSources()) s.insert(f.path);
        return s;
    }();
    return paths;
}

// The embedded path a quoted include of `name` from the file at `includer` means, or "" if none.
std::string resolve(const std::string& name, const std::string& includer) {
    namespace fs = std::filesystem;
    const std::string besideIncluder = (fs::path(includer).parent_path() / name).lexically_normal().generic_string();
    if (embeddedPaths().count(besideIncluder)) return besideIncluder;
    const std::string atRoot = fs::path(name).lexically_normal().generic_string();
    if (embeddedPaths().count(atRoot)) return atRoot;
    return "";
}

// If `line` is `#include "name"` (any spacing), its name's start and length.
bool quotedInclude(const std::string& line, size_t& nameStart, size_t& nameLength) {
    size_t i = line.find_first_not_of(" \t");
    if (i == std::string::npos || line[i] != '#') return false;
    i = line.find_first_not_of(" \t", i + 1);
    if (i == std::string::npos || line.compare(i, 7, "include") != 0) return false;
    i = line.find_first_not_of(" \t", i + 7);
    if (i == std::string::npos || line[i] != '"') return false;
    const size_t close = line.find('"', i + 1);
    if (close == std::string::npos) return false;
    nameStart = i + 1;
    nameLength = close - nameStart;
    return true;
}

}  // namespace

std::string resolveEmbeddedIncludes(const std::string& source, const std::string& path) {
    std::string out;
    out.reserve(source.size() + 64);
    size_t begin = 0;
    while (begin < source.size()) {
        size_t end = source.find('\n', begin);
        end = end == std::string::npos ? source.size() : end + 1;
        std::string line = source.substr(begin, end - begin);
        size_t start, length;
        if (quotedInclude(line, start, length)) {
            const std::string resolved = resolve(line.substr(start, length), path);
            if (!resolved.empty()) line.replace(start, length, resolved);
        }
        out += line;
        begin = end;
    }
    return out;
}

const NvrtcHeaders& nvrtcHeaders() {
    static const NvrtcHeaders headers = [] {
        NvrtcHeaders h;
        for (const jit::EmbeddedFile& f : jit::embeddedSources()) {
            h.names.emplace_back(f.path);
            h.contents.push_back(resolveEmbeddedIncludes(std::string(f.text, f.size), f.path));
        }
        return h;
    }();
    return headers;
}

}  // namespace deme::cuda
