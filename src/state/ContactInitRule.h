// A rule for the contact wildcards of pairs entering the contact set (SetFamilyContactWildcardInitValue):
// pairs between families a and b (either way round) start with `value` in wildcard `index` instead
// of 0. Plain data, for the host's tables and the GPU's kernels alike.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

struct ContactInitRule {
    family_t a, b;
    unsigned int index;
    float value;
};

}  // namespace deme
