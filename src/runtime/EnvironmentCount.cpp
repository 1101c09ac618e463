#include "runtime/EnvironmentCount.h"

#include <cstdlib>
#include <string>

#include <deme/Error.h>

namespace deme {

bool environmentCount(const char* name, const char* call, const char* what, size_t& out) {
    const char* p = std::getenv(name);
    if (!p) return false;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(p, &end, 10);
    if (!*p || *end || *p == '-' || *p == '+') throwError(call, std::string(name) + " is \"" + p + "\", not " + what);
    out = (size_t)v;
    return true;
}

}  // namespace deme
