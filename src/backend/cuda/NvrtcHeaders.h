// The embedded sources (jit/EmbeddedSources.h) as NVRTC's in-memory headers.
//
// NVRTC finds an in-memory header only by the exact name an #include spells, and does not resolve a
// quoted include relative to the including header (physics/BuiltInForceModels.h's "Quaternion.h"
// stays "Quaternion.h"). So each quoted include of an embedded file is respelled with the file's
// path from the include root, by the rule cmake/EmbedSources.cmake checks at build time: next to the
// including file first, then at the root. Only include lines change, and each stays one line, so
// NVRTC's line numbers are the files' own.
#pragma once

#include <string>
#include <vector>

namespace deme::cuda {

struct NvrtcHeaders {
    std::vector<std::string> names;     // "physics/Quaternion.h", "deme/VectorTypes.h", ...
    std::vector<std::string> contents;  // the files' text with includes respelled
};

// Built once per process from embeddedSources().
const NvrtcHeaders& nvrtcHeaders();

// `source`, a file at include path `path` (e.g. "backend/cuda/kernels/Example.cu", or any name for
// generated code, whose includes then resolve at the root), with its quoted includes of embedded files
// respelled as above.
std::string resolveEmbeddedIncludes(const std::string& source, const std::string& path);

}  // namespace deme::cuda
