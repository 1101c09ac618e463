#include "state/SphereLayoutChoice.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <numeric>

#include "state/OwnerCentre.h"

namespace deme {

bool fullSphereLayoutForced() {
    const char* v = std::getenv("DEME_FULL_SPHERE_LAYOUT");
    return v && std::strcmp(v, "0") != 0 && *v;
}

namespace {

template <class T>
void releaseStorage(std::vector<T>& v) {
    std::vector<T>().swap(v);  // (clear() would keep the storage)
}

}  // namespace

void ownerSphereRanges(const SimState& s, std::vector<uint32_t>& start) {
    if (!s.spheresAreOwners || s.spheres.owner.size() == s.spheres.size())
        return rangesByOwner(s.owners.size(), s.spheres.owner, start);
    // Owner o's sphere is sphere o; the owners after the clumps have none.
    const size_t nO = s.owners.size(), nS = s.spheres.size();
    start.resize(nO + 1);
    for (size_t o = 0; o <= nO; o++) start[o] = (uint32_t)std::min(o, nS);
}

void sphereOwners(const SimState& s, std::vector<bodyID_t>& owner) {
    if (!s.spheresAreOwners || s.spheres.owner.size() == s.spheres.size()) {
        owner = s.spheres.owner;
        return;
    }
    owner.resize(s.spheres.size());
    std::iota(owner.begin(), owner.end(), (bodyID_t)0);
}

void ownSphereOwners(SimState& s) {
    if (s.spheres.owner.size() == s.spheres.size()) return;
    sphereOwners(s, s.spheres.owner);
}

bool spheresCanBeOwners(const SimState& s) {
    const size_t nS = s.spheres.size();
    if (fullSphereLayoutForced() || nS == 0 || nS != s.numClumps) return false;
    if (s.spheresAreOwners) return true;  // sphere i is owner i's, its offset zero, by construction
    for (size_t i = 0; i < nS; i++)
        if (s.spheres.owner[i] != (bodyID_t)i) return false;
    for (const float3& r : s.spheres.relPos)
        if (!isZero(r)) return false;
    return true;
}

void chooseSphereLayout(SimState& s) {
    if (!spheresCanBeOwners(s)) {
        expandSphereLayout(s);
        return;
    }
    s.spheresAreOwners = true;
    releaseStorage(s.spheres.owner);     // sphere i's owner is owner i (sphereOwners)
    releaseStorage(s.ownerSphereStart);  // owner o's sphere is sphere o (ownerSphereRanges)
    releaseStorage(s.spheres.relPos);
    releaseStorage(s.cache.spherePos);
    releaseStorage(s.cache.sphereArm);
}

void expandSphereLayout(SimState& s) {
    if (!s.spheresAreOwners) return;
    const size_t nS = s.spheres.size();
    ownSphereOwners(s);
    s.spheresAreOwners = false;
    ownerSphereRanges(s, s.ownerSphereStart);
    s.spheres.relPos.assign(nS, make_float3(0.f, 0.f, 0.f));
    // The cache: a centred sphere's centre is its owner's, its arm zero.
    s.cache.spherePos.resize(nS);
    for (size_t i = 0; i < nS; i++) s.cache.spherePos[i] = ownerCentre(s, i);
    s.cache.sphereArm.assign(nS, make_float3(0.f, 0.f, 0.f));
}

}  // namespace deme
