// Arguments of the persistent-contact kernels (PersistentMerge.cu) shared with their host side
// (DevicePersistentContacts.cpp). Plain data only.
#pragma once

#include <deme/VariableTypes.h>

namespace deme {

// A contact set's pair keys: geometries A and B of n pairs, sorted by (A, B).
struct ContactKeys {
    const bodyID_t *geomA, *geomB;
    unsigned int n;
};

// Contacts that appear between families a and b (either way round) start with `value` in contact
// wildcard `index` (WildcardArrays::ContactInit, which SimState.h declares for the host only).
struct ContactInitRule {
    family_t a, b;
    unsigned int index;
    float value;
};

}  // namespace deme
