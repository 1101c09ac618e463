#include "state/SphereIds.h"

#include "state/SphereLayoutChoice.h"

namespace deme {

namespace {

template <class T>
void release(std::vector<T>& v) {
    std::vector<T>().swap(v);
}

}  // namespace

void shareSphereIdsWithOwners(SimState& s) {
    if (s.sphereIdsAreOwnerIds || fullSphereLayoutForced()) return;
    const size_t nS = s.spheres.size(), users = s.sphereUserToInternal.size();
    if (s.sphereInternalToUser.size() != nS || nS > s.ownerInternalToUser.size() ||
        users > s.ownerUserToInternal.size())
        return;
    for (size_t i = 0; i < nS; i++)
        if (s.sphereInternalToUser[i] != s.ownerInternalToUser[i]) return;
    for (size_t u = 0; u < users; u++)
        if (s.sphereUserToInternal[u] != s.ownerUserToInternal[u]) return;
    s.sphereIdsAreOwnerIds = true;
    s.userSphereIds = users;
    release(s.sphereInternalToUser);
    release(s.sphereUserToInternal);
}

void sphereIdMaps(const SimState& s, std::vector<bodyID_t>& internalToUser, std::vector<bodyID_t>& userToInternal) {
    if (!s.sphereIdsAreOwnerIds) {
        internalToUser = s.sphereInternalToUser;
        userToInternal = s.sphereUserToInternal;
        return;
    }
    internalToUser.assign(s.ownerInternalToUser.begin(), s.ownerInternalToUser.begin() + s.spheres.size());
    userToInternal.assign(s.ownerUserToInternal.begin(), s.ownerUserToInternal.begin() + s.userSphereIds);
}

void ownSphereIds(SimState& s) {
    if (!s.sphereIdsAreOwnerIds) return;
    std::vector<bodyID_t> internalToUser, userToInternal;
    sphereIdMaps(s, internalToUser, userToInternal);
    s.sphereIdsAreOwnerIds = false;
    s.userSphereIds = 0;
    s.sphereInternalToUser.swap(internalToUser);
    s.sphereUserToInternal.swap(userToInternal);
}

}  // namespace deme
