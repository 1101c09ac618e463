#include "runtime/IndexLimits.h"

#include <deme/Error.h>

#include <string>

namespace deme {

void requireIndexable(uint64_t count, const char* what, const char* remedy, const char* call) {
    if (count <= MAX_INDEXED_ITEMS) return;
    throwError(call, std::to_string(count) + " " + what + " are more than the " + std::to_string(MAX_INDEXED_ITEMS) +
                         " that 32-bit indices address; " + remedy);
}

}  // namespace deme
