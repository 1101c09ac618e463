#include "runtime/RebuiltArrays.h"

#include <cstdlib>
#include <string>

#include <deme/Error.h>

#include "state/SimState.h"

namespace deme {

size_t keepRebuiltArraysUpTo(const char* call) {
    const char* p = std::getenv("DEME_SMALL_CONTACT_SET_BYTES");
    if (!p) return KEEP_REBUILT_ARRAYS_UP_TO;
    char* end = nullptr;
    const unsigned long long bytes = std::strtoull(p, &end, 10);
    if (end == p || *end != '\0')
        throwError(call, std::string("DEME_SMALL_CONTACT_SET_BYTES is \"") + p + "\", not a number of bytes");
    return (size_t)bytes;
}

}  // namespace deme
