// What one force pass reports besides the per-contact forces it stores.
#pragma once

#include <cstddef>

namespace deme {

struct ForcePassResult {
    size_t realContacts = 0;  // pairs with overlap > 0 (mesh contacts only where they count)
    size_t realSphereSphere = 0;
};

}  // namespace deme
