// When a synchronous detection trims the set in use to the pairs that hand something to the next
// set (docs/memory.md, "A re-detection's peak"): both backends follow these rules (the CPU in
// backend/cpu/CarriedPairs.cpp, the GPU in CudaDynamics::beforeDetectNow).
#pragma once

#include <cstddef>
#include <cstdlib>
#include <cstring>

namespace deme {

// Not where a contact-init rule is set (new pairs would get its values, found pairs of zeros not),
// nor with DEME_KEEP_WHOLE_SET=1 (tests compare the two: the trajectory is the same).
inline bool mayKeepOnlyPairsHandedOn(bool contactInitRules) {
    if (contactInitRules) return false;
    const char* v = std::getenv("DEME_KEEP_WHOLE_SET");
    return !(v && std::strcmp(v, "1") == 0);
}

// Once counted: only where at most half of the pairs hand something on (a settled bed, where most
// do, would pay a pass of copies for little) and some do not.
inline bool keepingOnlyPairsHandedOnPays(size_t pairs, size_t handedOn) {
    return 2 * handedOn <= pairs && handedOn < pairs;
}

}  // namespace deme
