// How vectors read in messages, the same everywhere: "(x, y, z)".
#pragma once

#include <string>

#include <deme/VectorTypes.h>

namespace deme {

inline std::string formatVector(const float3& v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

}  // namespace deme
