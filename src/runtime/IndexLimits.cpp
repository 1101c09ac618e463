#include "runtime/IndexLimits.h"

#include <deme/Error.h>

#include <string>

namespace deme {

void requireIndexable(uint64_t count, const char* what, const char* remedy, const char* call) {
    if (count <= MAX_INDEXED_ITEMS) return;
    throwError(call, std::to_string(count) + " " + what + " are more than the " + std::to_string(MAX_INDEXED_ITEMS) +
                         " that 32-bit indices address; " + remedy);
}

void requireGpuPairCount(uint64_t pairs, const char* call) {
    if (pairs <= MAX_GPU_CONTACT_PAIRS) return;
    throwError(call, std::to_string(pairs) + " contact pairs are more than the " +
                         std::to_string(MAX_GPU_CONTACT_PAIRS) + " a GPU contact set holds; " + FEWER_PAIRS_REMEDY);
}

}  // namespace deme
