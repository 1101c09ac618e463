#include "runtime/AllocatorPolicy.h"

#include <cstdlib>
#include <initializer_list>
#include <mutex>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace deme {

bool allocatorTunedByUser() {
    for (const char* name :
         {"MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_", "MALLOC_TOP_PAD_", "MALLOC_MMAP_MAX_", "GLIBC_TUNABLES"})
        if (std::getenv(name)) return true;
    return false;
}

bool fixLargeBlockBound() {
    static std::once_flag once;
    static bool fixed = false;
    std::call_once(once, [] {
#if defined(__GLIBC__)
        // The heap's top is given back from 128 KiB free, glibc's default, which a large block freed
        // before this call may have raised.
        if (!allocatorTunedByUser())
            fixed =
                mallopt(M_MMAP_THRESHOLD, (int)LARGE_BLOCK_BYTES) == 1 && mallopt(M_TRIM_THRESHOLD, 128 * 1024) == 1;
#endif
    });
    return fixed;
}

void returnFreedHeapPages() {
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
}

}  // namespace deme
