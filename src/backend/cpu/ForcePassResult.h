// What one force pass reports besides the per-contact forces it stores, and how it stores them.
#pragma once

#include <cstddef>

namespace deme {

// Which per-contact forces a CPU force pass keeps for readers (the contact file, stress): none (a
// step no call ends after), those of the pairs with a force with their indices (ContactArrays::
// stored: nothing for a set of pairs within the margin but apart, as in a loose or fast flow), or
// every pair's (ContactArrays::force: fewer bytes than the indexed list where over 3/4 of the pairs
// touch, as in a packed bed, and a plain store per pair).
enum class ForceStore { NONE, PAIRS_WITH_FORCE, EVERY_PAIR };

struct ForcePassResult {
    size_t realContacts = 0;  // pairs with overlap > 0 (mesh contacts only where they count)
    size_t realSphereSphere = 0;
};

}  // namespace deme
