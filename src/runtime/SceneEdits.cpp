#include "runtime/SceneEdits.h"

#include <algorithm>
#include <string>
#include <type_traits>

#include <deme/Error.h>

#include "state/SphereLayoutChoice.h"
#include "state/SphereIds.h"

namespace deme {

namespace {

constexpr bodyID_t REMOVED = SimState::REMOVED_ID;

// Keeps the rows i of `v` with keep[i] (each row `stride` elements), in order.
template <class T>
void compact(std::vector<T>& v, const std::vector<uint8_t>& keep, size_t stride = 1) {
    size_t to = 0;
    for (size_t i = 0; i < keep.size(); i++) {
        if (!keep[i]) continue;
        for (size_t k = 0; k < stride; k++) v[to * stride + k] = v[i * stride + k];
        to++;
    }
    v.resize(to * stride);
}

// new index of each kept row (REMOVED for the others).
std::vector<bodyID_t> renumber(const std::vector<uint8_t>& keep) {
    std::vector<bodyID_t> to(keep.size(), REMOVED);
    bodyID_t next = 0;
    for (size_t i = 0; i < keep.size(); i++)
        if (keep[i]) to[i] = next++;
    return to;
}

// Spheres of owner o: [start[o], start[o + 1]).
void rebuildOwnerRanges(SimState& s) {
    rangesByOwner(s.owners.size(), s.spheres.owner, s.ownerSphereStart);  // (let go where spheres are owners)
}

// The per-step scratch and the CPU's per-owner contact index follow the owner count; the index is
// rebuilt when the next detection installs its set (which an edit always causes).
void resizeDerived(SimState& s) {
    s.integrationScratch.flags.assign(s.owners.size(), 0);
    ContactArrays& c = s.contacts;
    c.resetIndex(true);
}

}  // namespace

void insertClumps(SimState& s, const SimState& part) {
    if (!s.owners.holdsResults()) throwError("UpdateClumps", "internal: the state edited lacks its owners' results");
    // The rows are read as full sphere arrays with their own id maps (UpdateClumps assembles them
    // so); rows whose spheres are their owners are expanded first.
    if (part.spheresAreOwners || part.sphereIdsAreOwnerIds) {
        SimState full = part;
        expandSphereLayout(full);
        ownSphereIds(full);
        return insertClumps(s, full);
    }
    const size_t k = part.owners.size(), kS = part.spheres.size();
    const bodyID_t at = (bodyID_t)s.numClumps;  // where the new owners go
    const bodyID_t nS = (bodyID_t)s.spheres.size();
    const inertiaID_t massBase = (inertiaID_t)s.massProps.mass.size();
    const bodyID_t userOwnerBase = (bodyID_t)s.ownerUserToInternal.size();
    ownSphereIds(s);  // (shared again below where they can be)
    const bodyID_t userSphereBase = (bodyID_t)s.sphereUserToInternal.size();
    if (s.owners.size() + k >= (size_t(1) << 31) || s.sphereUserToInternal.size() + kS >= (size_t(1) << 31))
        throwError("UpdateClumps", "too many owners or spheres for 32-bit ids");
    // The new rows come with their offsets: the full sphere arrays for the edit, the layout chosen
    // again after it (state/SphereLayout.h).
    expandSphereLayout(s);

    // Owners: every field's new rows at `at`; the analytical and mesh owners move up by k.
    // (The edited state holds every owner's results, Simulation::wholeState; an assembled part has
    // none, state/SimState.h: its owners' start at zero.)
    forEachOwnerField(s.owners, part.owners, [at, k](auto& mine, const auto& theirs, FieldRole role) {
        if (role == FieldRole::RESULT && theirs.size() != k)
            mine.insert(mine.begin() + at, k, typename std::decay_t<decltype(mine)>::value_type{});
        else
            mine.insert(mine.begin() + at, theirs.begin(), theirs.end());
    });
    // Loads added before the edit stay with their owners; the new owners have none.
    if (!s.trackerLoads.empty())
        forEachTrackerLoadField(s.trackerLoads, s.trackerLoads, [at, k](auto& mine, auto&, FieldRole) {
            mine.insert(mine.begin() + at, k, typename std::decay_t<decltype(mine)>::value_type{});
        });
    for (size_t j = 0; j < k; j++) s.owners.inertia[at + j] += massBase;
    forEachMassField(s.massProps, part.massProps,
                     [](auto& mine, const auto& theirs, FieldRole) { mine.insert(mine.end(), theirs.begin(), theirs.end()); });
    for (bodyID_t& o : s.analytical.owner) o += (bodyID_t)k;
    for (bodyID_t& o : s.triangles.owner) o += (bodyID_t)k;
    for (bodyID_t& o : s.ownerUserToInternal)
        if (o != REMOVED && o >= at) o += (bodyID_t)k;
    for (size_t j = 0; j < k; j++) s.ownerUserToInternal.push_back(at + part.ownerUserToInternal[j]);
    std::vector<bodyID_t> newUsers(k);
    for (size_t j = 0; j < k; j++) newUsers[j] = userOwnerBase + part.ownerInternalToUser[j];
    s.ownerInternalToUser.insert(s.ownerInternalToUser.begin() + at, newUsers.begin(), newUsers.end());
    for (size_t w = 0; w < s.wildcards.owner.size(); w++) {
        std::vector<float>& v = s.wildcards.owner[w];
        v.insert(v.begin() + at, part.wildcards.owner[w].begin(), part.wildcards.owner[w].end());
    }

    // Spheres: appended (the new clumps' spheres are the last, as the new clumps are the last
    // clumps); the analytical and triangle geometry ids move up by kS.
    forEachSphereField(s.spheres, part.spheres, [](auto& mine, const auto& theirs, FieldRole) {
        mine.insert(mine.end(), theirs.begin(), theirs.end());
    });
    for (size_t i = nS; i < nS + kS; i++) s.spheres.owner[i] += at;
    for (size_t i = 0; i < kS; i++) {
        s.sphereInternalToUser.push_back(userSphereBase + part.sphereInternalToUser[i]);
        s.sphereUserToInternal.push_back(nS + part.sphereUserToInternal[i]);
    }
    for (size_t w = 0; w < s.wildcards.geometry.size(); w++) {
        std::vector<float>& v = s.wildcards.geometry[w];
        const std::vector<float>& p = part.wildcards.geometry[w];
        v.insert(v.begin() + nS, p.begin(), p.begin() + kS);
    }
    // Contacts: side A is always a sphere (unchanged); side B moves with its kind.
    for (bodyID_t& g : s.contacts.geomB)
        if (g >= nS) g += (bodyID_t)kS;

    s.numClumps += k;
    rebuildOwnerRanges(s);
    resizeDerived(s);
    chooseSphereLayout(s);
    shareSphereIdsWithOwners(s);
}

RemovedClumps removeClumps(SimState& s, const std::vector<uint8_t>& remove) {
    const size_t n = s.owners.size(), nS = s.spheres.size(), nA = s.analytical.size(), nT = s.triangles.size();
    if (!s.owners.holdsResults()) throwError("RemoveClumps", "internal: the state edited lacks its owners' results");
    RemovedClumps r;
    std::vector<uint8_t> keepOwner(n, 1);
    for (size_t o = 0; o < n; o++) {
        if (!remove[o]) continue;
        if (o >= s.numClumps) throwError("RemoveClumps", "internal: owner " + std::to_string(o) + " is not a clump");
        keepOwner[o] = 0;
        r.count++;
        r.mass += (double)s.massProps.mass[s.owners.inertia[o]];
    }
    if (r.count == 0) return r;
    ownSphereIds(s);     // (shared again below where they can be)
    ownSphereOwners(s);  // (let go again below where spheres stay their owners)
    const std::vector<bodyID_t> newOwner = renumber(keepOwner);
    std::vector<uint8_t> keepSphere(nS);
    for (size_t i = 0; i < nS; i++) keepSphere[i] = keepOwner[s.spheres.owner[i]];
    const std::vector<bodyID_t> newSphere = renumber(keepSphere);
    const bodyID_t nSKept = (bodyID_t)(nS - (size_t)std::count(keepSphere.begin(), keepSphere.end(), 0));
    // Geometry ids: spheres renumbered, the analytical components and triangles after them.
    auto newGeometry = [&](bodyID_t g) { return g < nS ? newSphere[g] : (bodyID_t)(g - nS + nSKept); };

    // The contact set: pairs with a removed sphere go, the others are renamed (still sorted).
    ContactArrays& c = s.contacts;
    const size_t nC = c.size();
    std::vector<uint8_t> keepContact(nC);
    for (size_t i = 0; i < nC; i++) keepContact[i] = keepSphere[c.geomA[i]] && (c.geomB[i] >= nS || keepSphere[c.geomB[i]]);
    for (size_t i = 0; i < nC; i++) {
        c.geomA[i] = newGeometry(c.geomA[i]);
        c.geomB[i] = keepContact[i] ? newGeometry(c.geomB[i]) : c.geomB[i];
    }
    if (nC)
        forEachContactField(c, c, [&](auto& field, auto&, FieldRole) {
            // Per-pair fields (wildcards: W per pair); the CPU's indices are rebuilt below anyway.
            if (field.empty() || field.size() % nC) return;
            compact(field, keepContact, field.size() / nC);
        });

    // Owners, spheres, and the references between them.
    forEachOwnerField(s.owners, s.owners, [&](auto& field, auto&, FieldRole) { compact(field, keepOwner); });
    if (!s.trackerLoads.empty())
        forEachTrackerLoadField(s.trackerLoads, s.trackerLoads,
                                [&](auto& field, auto&, FieldRole) { compact(field, keepOwner); });
    // (Spheres that are their owners have no offsets: state/SphereLayout.h. They stay so.)
    forEachSphereField(s.spheres, s.spheres, [&](auto& field, auto&, FieldRole) {
        if (field.size() == nS) compact(field, keepSphere);
    });
    for (bodyID_t& o : s.spheres.owner) o = newOwner[o];
    for (bodyID_t& o : s.analytical.owner) o = newOwner[o];
    for (bodyID_t& o : s.triangles.owner) o = newOwner[o];
    for (bodyID_t& o : s.ownerUserToInternal)
        if (o != REMOVED) o = newOwner[o];
    compact(s.ownerInternalToUser, keepOwner);
    for (bodyID_t& i : s.sphereUserToInternal)
        if (i != REMOVED) i = newSphere[i];
    compact(s.sphereInternalToUser, keepSphere);
    for (std::vector<float>& v : s.wildcards.owner) compact(v, keepOwner);
    std::vector<uint8_t> keepGeometry(keepSphere);
    keepGeometry.resize(nS + nA + nT, 1);
    for (std::vector<float>& v : s.wildcards.geometry) compact(v, keepGeometry);

    s.numClumps -= r.count;
    s.numRemovedClumps += r.count;
    s.removedMass += r.mass;
    rebuildOwnerRanges(s);
    resizeDerived(s);
    chooseSphereLayout(s);
    shareSphereIdsWithOwners(s);
    return r;
}

bodyID_t liveOwner(const SimState& s, size_t user, const char* call) {
    if (user >= s.ownerUserToInternal.size())
        throwError(call, "owner id " + std::to_string(user) + " is out of range (ids issued so far: " +
                             std::to_string(s.ownerUserToInternal.size()) +
                             "; clumps added after Initialize exist once UpdateClumps() has run)");
    const bodyID_t o = s.ownerUserToInternal[user];
    if (o == REMOVED) throwError(call, "owner " + std::to_string(user) + " was removed from the simulation");
    return o;
}

bodyID_t liveSphere(const SimState& s, size_t user, const char* call) {
    if (user >= userSphereCount(s))
        throwError(call, "sphere id " + std::to_string(user) +
                             " is out of range (ids issued so far: " + std::to_string(userSphereCount(s)) + ")");
    const bodyID_t i = sphereInternalId(s, user);
    if (i == REMOVED) throwError(call, "sphere " + std::to_string(user) + " was removed from the simulation");
    return i;
}

}  // namespace deme
