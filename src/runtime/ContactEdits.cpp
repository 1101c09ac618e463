#include "runtime/ContactEdits.h"

#include <algorithm>

#include "dynamics/ContactInputsGather.h"
#include "state/SphereLayout.h"

namespace deme {

namespace {

template <class Edit>
size_t forSelected(SimState& s, const FamilySelector& which, Edit edit) {
    const ContactArrays& c = s.contacts;
    size_t n = 0;
    for (size_t i = 0; i < c.size(); i++) {
        const family_t fa = s.owners.family[sphereOwner(s, c.geomA[i])];
        const family_t fb = s.owners.family[contactOwnerB(s, i)];
        if (!which.matches(fa, fb)) continue;
        edit(i);
        n++;
    }
    return n;
}

}  // namespace

size_t setContactPersistence(SimState& s, const FamilySelector& which, bool persistent) {
    return forSelected(s, which, [&](size_t i) { s.contacts.persistent[i] = persistent ? 1 : 0; });
}

size_t setContactWildcard(SimState& s, const FamilySelector& which, unsigned int index, float value) {
    const unsigned int W = s.numWildcards;
    return forSelected(s, which, [&](size_t i) { s.contacts.wildcards[i * W + index] = value; });
}

size_t countPersistentContacts(const SimState& s) {
    return (size_t)std::count(s.contacts.persistent.begin(), s.contacts.persistent.end(), 1);
}

void addContactWildcardInit(WildcardArrays& w, const WildcardArrays::ContactInit& rule) {
    for (WildcardArrays::ContactInit& r : w.contactInit)
        if (r.index == rule.index && ((r.a == rule.a && r.b == rule.b) || (r.a == rule.b && r.b == rule.a))) {
            r = rule;
            return;
        }
    w.contactInit.push_back(rule);
}

}  // namespace deme
