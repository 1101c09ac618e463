#include "io/CheckpointState.h"

#include <map>
#include <type_traits>

#include <deme/Error.h>

#include "state/SphereIds.h"
#include "state/SphereLayoutChoice.h"

namespace deme {

namespace {

// f(name, array, role) for every field of one group, straight from the lists, with the field's
// name (state/StateFields.h's visitors give no names).
#define DEME_NAMED_FIELD(name, T, role) f(#name, g.name, FieldRole::role);
#define DEME_NAMED_VISITOR(Fn, LIST)          \
    template <class G, class F>               \
    void Fn(G& g, F&& f) {                    \
        LIST(DEME_NAMED_FIELD)                \
    }
DEME_NAMED_VISITOR(namedOwnerFields, DEME_OWNER_FIELDS)
DEME_NAMED_VISITOR(namedTrackerLoadFields, DEME_TRACKER_LOAD_FIELDS)
DEME_NAMED_VISITOR(namedMassFields, DEME_MASS_FIELDS)
DEME_NAMED_VISITOR(namedSphereFields, DEME_SPHERE_FIELDS)
DEME_NAMED_VISITOR(namedAnalyticalFields, DEME_ANALYTICAL_FIELDS)
DEME_NAMED_VISITOR(namedTriangleFields, DEME_TRIANGLE_FIELDS)
DEME_NAMED_VISITOR(namedContactFields, DEME_CONTACT_FIELDS)
DEME_NAMED_VISITOR(namedCacheFields, DEME_CACHE_FIELDS)
#undef DEME_NAMED_VISITOR
#undef DEME_NAMED_FIELD

// Every array a checkpoint holds, as f("group.field", vector): the listed groups' EVOLVES, RESULT and
// INPUT fields (SCRATCH is a step's own, HOST the CPU's bookkeeping, rebuilt at the next detection), then
// the host tables. The kinematic cache is derived from the poses, but stored all the same: the
// integration's vectorised loop and the host's refresh (dynamics/KinematicCache.h) may round the
// sphere centres differently, and a restart that recomputed them would not be bit for bit.
template <class S, class F>
void forEachStoredArray(S& s, F&& f) {
    auto group = [&](const char* prefix) {
        return [&f, prefix](const char* name, auto& field, FieldRole role) {
            if (role != FieldRole::SCRATCH && role != FieldRole::HOST) f(std::string(prefix) + "." + name, field);
        };
    };
    namedOwnerFields(s.owners, group("owners"));
    namedTrackerLoadFields(s.trackerLoads, group("trackerLoads"));  // empty unless loads are pending
    namedMassFields(s.massProps, group("massProps"));
    namedSphereFields(s.spheres, group("spheres"));
    namedAnalyticalFields(s.analytical, group("analytical"));
    namedTriangleFields(s.triangles, group("triangles"));
    namedContactFields(s.contacts, group("contacts"));
    namedCacheFields(s.cache, group("cache"));
    f("ownerSphereStart", s.ownerSphereStart);
    f("ownerUserToInternal", s.ownerUserToInternal);
    f("ownerInternalToUser", s.ownerInternalToUser);
    f("sphereInternalToUser", s.sphereInternalToUser);
    f("sphereUserToInternal", s.sphereUserToInternal);
}

struct Record {
    uint32_t elemSize = 0;
    uint64_t count = 0;
    const char* bytes = nullptr;
};

}  // namespace

void writeStateSection(const SimState& s, ByteWriter& out) {
    out.value((uint64_t)s.numClumps);
    out.value((uint64_t)s.numAnalyticalOwners);
    out.value((uint32_t)s.numWildcards);
    out.value((uint8_t)!s.trackerLoads.empty());
    out.value((uint64_t)s.numRemovedClumps);  // RemoveClumpsInFamily and the "remove" exit policy
    out.value(s.removedMass);
    uint64_t records = 0;
    forEachStoredArray(s, [&](const std::string&, const auto&) { records++; });
    records += s.wildcards.owner.size() + s.wildcards.geometry.size();
    out.value(records);
    // Sphere id maps shared with the owners' (state/SphereIds.h) are written as the maps they are.
    std::vector<bodyID_t> sphereToUser, userToSphere;
    if (s.sphereIdsAreOwnerIds) sphereIdMaps(s, sphereToUser, userToSphere);
    // So are the owners' sphere ranges and the spheres' owners where spheres are their owners
    // (state/SphereLayoutChoice.h).
    std::vector<uint32_t> sphereRanges;
    std::vector<bodyID_t> owners;
    if (s.spheresAreOwners) {
        ownerSphereRanges(s, sphereRanges);
        sphereOwners(s, owners);
    }
    forEachStoredArray(s, [&](const std::string& name, const auto& v) {
        out.text(name);
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::vector<bodyID_t>>) {
            if (s.sphereIdsAreOwnerIds && name == "sphereInternalToUser") return out.array(sphereToUser);
            if (s.sphereIdsAreOwnerIds && name == "sphereUserToInternal") return out.array(userToSphere);
            if (s.spheresAreOwners && name == "spheres.owner") return out.array(owners);
        }
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::vector<uint32_t>>) {
            if (s.spheresAreOwners && name == "ownerSphereStart") return out.array(sphereRanges);
        }
        out.array(v);
    });
    for (size_t i = 0; i < s.wildcards.owner.size(); i++) {
        out.text("wildcards.owner." + std::to_string(i));
        out.array(s.wildcards.owner[i]);
    }
    for (size_t i = 0; i < s.wildcards.geometry.size(); i++) {
        out.text("wildcards.geometry." + std::to_string(i));
        out.array(s.wildcards.geometry[i]);
    }
    // Rules for contact wildcards of pairs entering the set (field by field: the struct has padding).
    out.value((uint64_t)s.wildcards.contactInit.size());
    for (const ContactInitRule& r : s.wildcards.contactInit) {
        out.value(r.a);
        out.value(r.b);
        out.value((uint32_t)r.index);
        out.value(r.value);
    }
}

void readStateSection(ByteReader& in, SimState& s, const std::string& call, const std::string& path, uint32_t version,
                      std::vector<double>& travelSinceStart) {
    const std::string file = "\"" + path + "\"";
    auto layout = [&](const std::string& what) {
        throwError(call, file + " holds a state of another layout than this build's: " + what +
                             " (written by another version of the engine?)");
    };
    // The file holds the sphere id maps themselves: shared with the owners' again below, if equal.
    s.sphereIdsAreOwnerIds = false;
    s.userSphereIds = 0;
    s.numClumps = (size_t)in.value<uint64_t>("the clump count");
    s.numAnalyticalOwners = (size_t)in.value<uint64_t>("the analytical owner count");
    s.numWildcards = in.value<uint32_t>("the contact wildcard count");
    const bool trackerLoads = in.value<uint8_t>("the tracker load flag") != 0;
    s.numRemovedClumps = (size_t)in.value<uint64_t>("the removed clump count");
    s.removedMass = in.value<double>("the removed mass");
    const uint64_t n = in.value<uint64_t>("the record count");
    std::map<std::string, Record> records;
    for (uint64_t i = 0; i < n; i++) {
        const std::string name = in.text("a field name");
        Record r;
        r.elemSize = in.value<uint32_t>(name.c_str());
        r.count = in.value<uint64_t>(name.c_str());
        if (r.elemSize == 0 || r.count > (uint64_t)1 << 40) in.malformed("field " + name + " has an impossible size");
        r.bytes = in.take((size_t)(r.elemSize * r.count), name.c_str());
        if (!records.emplace(name, r).second) in.malformed("field " + name + " appears twice");
    }
    auto fill = [&](const std::string& name, auto& v) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        const auto it = records.find(name);
        if (it == records.end()) layout("it lacks field " + name);
        if (version == 1 && name == "owners.travel" && it->second.elemSize == sizeof(double)) {
            travelSinceStart.resize((size_t)it->second.count);
            if (!travelSinceStart.empty())
                std::memcpy(travelSinceStart.data(), it->second.bytes, travelSinceStart.size() * sizeof(double));
            v.assign(travelSinceStart.size(), T());
            records.erase(it);
            return;
        }
        if (it->second.elemSize != sizeof(T))
            layout("field " + name + " has elements of " + std::to_string(it->second.elemSize) + " bytes, this build's " +
                   std::to_string(sizeof(T)));
        v.resize((size_t)it->second.count);
        if (!v.empty()) std::memcpy(v.data(), it->second.bytes, v.size() * sizeof(T));
        records.erase(it);
    };
    s.contacts.aAsRuns = false;  // the file holds every pair's A
    forEachStoredArray(s, fill);
    // Fields that earlier builds wrote and this one derives: a pair's type follows from B
    // (state/ContactTypeOf.h).
    records.erase("contacts.type");
    // ... and each owner's range of triangles (nothing reads them: a mesh's triangles are one run).
    records.erase("ownerTriStart");
    // ... and each owner's type (its place among the owners, state/OwnerTypeOf.h).
    records.erase("owners.type");
    // Owner and geometry wildcards: as many as the force model declares (the fingerprint checked it).
    for (size_t i = 0; i < s.wildcards.owner.size(); i++) fill("wildcards.owner." + std::to_string(i), s.wildcards.owner[i]);
    for (size_t i = 0; i < s.wildcards.geometry.size(); i++)
        fill("wildcards.geometry." + std::to_string(i), s.wildcards.geometry[i]);
    if (!records.empty()) layout("this build does not know its field " + records.begin()->first);

    const uint64_t rules = in.value<uint64_t>("the contact wildcard rule count");
    s.wildcards.contactInit.clear();
    for (uint64_t i = 0; i < rules; i++) {
        ContactInitRule r;
        r.a = in.value<family_t>("a contact wildcard rule");
        r.b = in.value<family_t>("a contact wildcard rule");
        r.index = in.value<uint32_t>("a contact wildcard rule");
        r.value = in.value<float>("a contact wildcard rule");
        if (r.index >= s.numWildcards) in.malformed("a contact wildcard rule names wildcard " + std::to_string(r.index));
        s.wildcards.contactInit.push_back(r);
    }
    if (!in.atEnd()) in.malformed("the state section has bytes after its end");

    // Lengths that must agree (a checksum cannot catch a writer's mistake).
    const size_t nO = s.owners.size(), nS = s.spheres.size(), nA = s.analytical.size(), nT = s.triangles.size();
    auto require = [&](bool ok, const std::string& what) {
        if (!ok) in.malformed(what);
    };
    namedOwnerFields(s.owners, [&](const char* name, const auto& v, FieldRole) {
        require(v.size() == nO, std::string("owners.") + name + " is not one value per owner");
    });
    namedTrackerLoadFields(s.trackerLoads, [&](const char* name, const auto& v, FieldRole) {
        require(v.size() == (trackerLoads ? nO : 0), std::string("trackerLoads.") + name + " does not fit its flag");
    });
    if (!trackerLoads) s.trackerLoads.release();  // loads pending before the read held storage
    // Spheres that are their owners (state/SphereLayout.h) were written without offsets, centres or
    // arms: the state takes the layout it was written in.
    s.spheresAreOwners = nS > 0 && s.spheres.relPos.empty();
    const size_t placed = s.spheresAreOwners ? 0 : nS;  // offsets, centres, arms
    namedSphereFields(s.spheres, [&](const char* name, const auto& v, FieldRole) {
        const bool offsets = static_cast<const void*>(&v) == static_cast<const void*>(&s.spheres.relPos);
        require(v.size() == (offsets ? placed : nS), std::string("spheres.") + name + " is not one value per sphere");
    });
    require(s.cache.spherePos.size() == placed && s.cache.sphereArm.size() == placed,
            "the cached sphere centres do not fit the spheres");
    if (s.spheresAreOwners) {
        require(s.numClumps == nS, "spheres without offsets, but not one per clump");
        for (size_t i = 0; i < nS; i++)
            require(s.spheres.owner[i] == (bodyID_t)i, "spheres without offsets, but not their owners'");
    }
    namedAnalyticalFields(s.analytical, [&](const char* name, const auto& v, FieldRole) {
        require(v.size() == nA, std::string("analytical.") + name + " is not one value per component");
    });
    const size_t nC = s.contacts.size();
    namedContactFields(s.contacts, [&](const char* name, const auto& v, FieldRole role) {
        if (role == FieldRole::HOST) return;
        const size_t want = std::string(name) == "wildcards" ? nC * s.numWildcards : nC;
        // Per-contact forces are the last step's output, not state: a CPU run keeps them elsewhere
        // (ContactArrays::stored) and writes none.
        const bool noForces = std::string(name) == "force" && v.empty();
        // A scene without triangles keeps no mesh state (backend/cpu/HistoryMapping.cpp).
        const bool noMeshState = std::string(name) == "meshState" && v.empty() && nT == 0;
        require(v.size() == want || noForces || noMeshState,
                std::string("contacts.") + name + " does not fit the contact count");
    });
    require(s.numClumps + s.numAnalyticalOwners <= nO, "more clumps and analytical owners than owners");
    require(s.ownerSphereStart.size() == nO + 1, "the per-owner sphere ranges");
    // (User ids are never reused: after removals the user-to-internal maps are the longer ones.)
    require(s.ownerUserToInternal.size() >= nO && s.ownerInternalToUser.size() == nO, "the owner id maps");
    require(s.sphereUserToInternal.size() >= nS && s.sphereInternalToUser.size() == nS, "the sphere id maps");
    for (const auto& w : s.wildcards.owner) require(w.size() == nO, "an owner wildcard is not one value per owner");
    for (const auto& w : s.wildcards.geometry)
        require(w.size() == nS + nA + nT, "a geometry wildcard is not one value per geometry");
    const uint64_t nGeom = nS + nA + nT;
    for (size_t c = 0; c < nC; c++)
        require(s.contacts.geomA[c] < nGeom && s.contacts.geomB[c] < nGeom, "a contact names a geometry that is not there");
    // The CPU's contact bookkeeping belongs to the set it was built for: rebuilt at the next
    // detection, which a restored state always gets first.
    namedContactFields(s.contacts, [&](const char*, auto& v, FieldRole role) {
        if (role == FieldRole::HOST) v.clear();
    });
    shareSphereIdsWithOwners(s);
    if (s.spheresAreOwners) {  // as the layout keeps them: none
        std::vector<uint32_t>().swap(s.ownerSphereStart);
        std::vector<bodyID_t>().swap(s.spheres.owner);
    }
}

}  // namespace deme
