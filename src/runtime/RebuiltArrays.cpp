#include "runtime/RebuiltArrays.h"

#include "runtime/EnvironmentCount.h"
#include "state/SimState.h"

namespace deme {

size_t keepRebuiltArraysUpTo(const char* call) {
    size_t bytes = KEEP_REBUILT_ARRAYS_UP_TO;
    environmentCount("DEME_SMALL_CONTACT_SET_BYTES", call, "a number of bytes", bytes);
    return bytes;
}

}  // namespace deme
