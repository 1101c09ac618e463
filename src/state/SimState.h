// The simulation's flat structure-of-arrays state on the host, built at Initialize() (paper §2.3,
// §2.4): the arrays of state/StateFields.h as std::vectors, plus the tables and scalars that only
// the host side reads. Owners carry mass, pose, velocity and family; geometries (spheres,
// analytical components, triangles) carry shape and material and point at their owner. Contacts
// are between geometries.
#pragma once

#include <algorithm>
#include <type_traits>
#include <vector>

#include <deme/VariableTypes.h>

#include "physics/CompactPosition.h"
#include "state/ContactInitRule.h"
#include "state/PooledHistory.h"
#include "state/StateFields.h"

namespace deme {

template <class T>
using HostArray = std::vector<T>;

struct OwnerArrays : OwnerFields<HostArray> {
    size_t size() const { return voxel.size(); }
    // The RESULT fields (state/StateFields.h: the last step's loads, the travel) held for every
    // owner: always on the CPU backend, whose steps run on these arrays; in a GPU run only while
    // fetched (Simulation::wholeState).
    bool holdsResults() const { return travel.size() == size(); }
    // Zero results for every owner where the host holds none (an assembled scene).
    void makeResults() {
        forEachOwnerField(*this, *this, [n = size()](auto& v, auto&, FieldRole role) {
            if (role == FieldRole::RESULT && v.size() != n) v.assign(n, {});
        });
    }
    // Lets the host's copy of the results go (their storage too).
    void releaseResults() {
        forEachOwnerField(*this, *this, [](auto& v, auto&, FieldRole role) {
            if (role == FieldRole::RESULT) std::decay_t<decltype(v)>().swap(v);
        });
    }
};
// Empty unless some owner has a tracker load for the coming call (state/StateFields.h).
struct TrackerLoadArrays : TrackerLoadFields<HostArray> {
    bool empty() const { return extraAcc.empty(); }
    // Zero loads for every owner, made on the first load of a call.
    void prepare(size_t numOwners) {
        if (!empty()) return;
        extraAcc.assign(numOwners, make_float3(0.f));
        extraAngAcc.assign(numOwners, make_float3(0.f));
    }
    // Releases the arrays' storage (an assignment of an empty vector would keep it).
    void release() {
        HostArray<float3>().swap(extraAcc);
        HostArray<float3>().swap(extraAngAcc);
    }
};
using MassProperties = MassFields<HostArray>;
struct SphereArrays : SphereFields<HostArray> {
    // (`owner` is empty where spheres are their owners; a state made field by field may lack radii)
    size_t size() const { return owner.size() > radius.size() ? owner.size() : radius.size(); }
};
struct AnalyticalArrays : AnalyticalFields<HostArray> {
    size_t size() const { return owner.size(); }
};
struct TriangleArrays : TriangleFields<HostArray> {
    size_t size() const { return owner.size(); }
};
// The CPU's per-contact forces of the last step that stored them (the last of a DoDynamics call):
// the pairs with a force only, contact index and force on A, in one list per thread of the force
// pass (backend/cpu/ForcePassLoop.h; runtime/ContactForceView.h reads them by contact). Emptied,
// with its capacity kept, by every pass; released where the set is rebuilt by an edit.
struct StoredContactForces {
    std::vector<std::vector<uint32_t>> index;
    std::vector<std::vector<float3>> force;
    size_t count() const {
        size_t n = 0;
        for (const std::vector<uint32_t>& v : index) n += v.size();
        return n;
    }
    void clear() {
        for (std::vector<uint32_t>& v : index) v.clear();
        for (std::vector<float3>& v : force) v.clear();
    }
};

// Arrays the CPU rebuilds at every detection (its bins, a set's index) are let go between
// detections, or before the arrays that replace them are made, where they hold more than this:
// a large scene's memory at its peak, and no new pages per detection for a small one (whose bytes
// do not matter; allocating them again made a 60,000-sphere bed's binning a third slower).
constexpr size_t KEEP_REBUILT_ARRAYS_UP_TO = 32u << 20;

struct ContactArrays : ContactFields<HostArray> {
    size_t size() const { return geomB.size(); }
    // The CPU's steps keep A as runs where spheres are their owners (backend/cpu/ContactARuns.h):
    // sphere o is then owner o, so the force reduction's runs (ownerAStart) give every pair's A and
    // geomA (4 B a pair) is let go. Whatever empties the index, or reads the set on the host, first
    // gets geomA back (restoreA).
    bool aAsRuns = false;
    // The owner of pair i's A, from the runs (the index must be built).
    size_t pairAOwner(size_t i) const {
        return (size_t)(std::upper_bound(ownerAStart.begin(), ownerAStart.end(), (uint32_t)i) - ownerAStart.begin()) -
               1;
    }
    // Pair i's A sphere.
    bodyID_t pairA(size_t i) const { return aAsRuns ? (bodyID_t)pairAOwner(i) : geomA[i]; }
    // geomA made again from the runs (one sphere per owner: A's owner is A).
    void restoreA() {
        if (!aAsRuns) return;
        geomA.resize(size());
        for (size_t o = 0; o + 1 < ownerAStart.size(); o++)
            std::fill(geomA.begin() + ownerAStart[o], geomA.begin() + ownerAStart[o + 1], (bodyID_t)o);
        aAsRuns = false;
    }
    StoredContactForces stored;  // the CPU's (a GPU run's host copy has `force` per contact)
    // The CPU steps' pooled form of the history (state/PooledHistory.h), in use where `wildcards`
    // is empty and the pool has a slot per pair: `wildcards` wins wherever it holds the history.
    PooledHistory pooled;
    bool historyPooled(unsigned int W) const {
        return W > 0 && size() > 0 && wildcards.empty() && pooled.pairs == size();
    }
    // Whether owner o is B of a contact whose A is in o's own block of the force pass (its share
    // is then summed in the pass, not in a window; backend/cpu/ForcePassLoop.h).
    bool isBInItsBlock(size_t o) const {
        return o / 64 < ownerBInBlock.size() && ((ownerBInBlock[o / 64] >> (o % 64)) & 1u);
    }
    // Empties what belongs to one set as it was indexed (backend/cpu/HistoryMapping.h): the
    // sphere-triangle runs, the force reduction's index and windows, the stored forces; their
    // memory is let go too where it is large (KEEP_REBUILT_ARRAYS_UP_TO) or `release` says so.
    void resetIndex(bool release = false) {
        // A kept as runs comes back before the runs go; the other arrays first, so that geomA is
        // made where they were.
        const bool restore = aAsRuns;
        const size_t bytes =
            sizeof(uint32_t) * (meshContacts.capacity() + meshContactGroups.capacity() + ownerAStart.capacity() +
                                blockWindowStart.capacity() + blockOutStart.capacity() + outSlotWide.capacity() +
                                ownerBStart.capacity() + ownerBSlots.capacity()) +
            sizeof(uint16_t) * outSlot.capacity() + sizeof(WindowLoad) * window.capacity() +
            sizeof(float3) * force.capacity() + sizeof(uint64_t) * ownerBInBlock.capacity();
        release = release || bytes > KEEP_REBUILT_ARRAYS_UP_TO;
        auto reset = [release](auto& v) {
            if (release)
                std::decay_t<decltype(v)>().swap(v);
            else
                v.clear();
        };
        reset(meshContacts);
        reset(meshContactGroups);
        reset(blockWindowStart);
        reset(blockOutStart);
        reset(outSlot);
        reset(outSlotWide);
        reset(window);
        reset(ownerBStart);
        reset(ownerBSlots);
        reset(ownerBInBlock);
        reset(force);
        if (release)
            stored = StoredContactForces();
        else
            stored.clear();
        if (restore) restoreA();
        reset(ownerAStart);
    }
};
using KinematicCache = CacheFields<HostArray>;
using IntegrationScratch = ScratchFields<HostArray>;

// Each of n owners' range of items [start[o], start[o + 1]) from the items' owners (which ascend).
inline void rangesByOwner(size_t n, const std::vector<bodyID_t>& ownerOf, std::vector<uint32_t>& start) {
    start.assign(n + 1, 0);
    for (bodyID_t o : ownerOf) start[o + 1]++;
    for (size_t o = 0; o < n; o++) start[o + 1] += start[o];
}

inline uint64_t contactKey(bodyID_t a, bodyID_t b) { return (uint64_t(a) << 32) | uint64_t(b); }

// Material property tables for the force model.
struct MaterialTables {
    unsigned int count = 0;
    // The standard properties, which the built-in models and the derived tables read (0 where a
    // material lacks one).
    std::vector<float> E, nu;         // per material
    std::vector<float> CoR, mu, Crr;  // per pair, count x count
    // Derived once per pair (MaterialMixing.h) so that force models need not mix per contact:
    // effective Young's and shear moduli, and the damping term of CoR.
    std::vector<float> E_eff, G_eff, beta_CoR;
    // Every property by name for a user's model, in the order of the model's layout
    // (forcemodel/ModelLayout.h): per-material ones, then the ones the model reads per pair.
    std::vector<std::vector<float>> props, pairProps;
};

// The force model's owner and geometry wildcards (paper Table 3): one array per wildcard, in the
// order the model declares them, indexed by internal owner id or unified geometry id. Contact
// wildcards live with the contacts (ContactArrays::wildcards).
struct WildcardArrays {
    std::vector<std::vector<float>> owner, geometry;
    // Contacts that appear between families a and b (either way round) start with `value` in
    // contact wildcard `index` instead of 0.
    using ContactInit = ContactInitRule;
    std::vector<ContactInit> contactInit;
};

struct SimState {
    DomainFrame frame;
    double3 domainSize;
    OwnerArrays owners;
    TrackerLoadArrays trackerLoads;
    MassProperties massProps;
    SphereArrays spheres;
    AnalyticalArrays analytical;
    TriangleArrays triangles;
    ContactArrays contacts;
    KinematicCache cache;
    IntegrationScratch integrationScratch;
    // Every clump one sphere at its centre, sphere i owner i's: no sphere offsets, centres or arms
    // are kept (state/SphereLayout.h; runtime/SphereLayoutChoice.h sets it).
    bool spheresAreOwners = false;
    // Spheres of owner o: [start[o], start[o+1]); empty where spheresAreOwners. (Triangles keep no
    // such ranges: nothing reads them, and a mesh's triangles are one run of triangles.owner.)
    std::vector<uint32_t> ownerSphereStart;
    // Owners and spheres are stored in a space-filling-curve order for memory locality; users see
    // ids in the order they added things (clumps batch by batch, then external objects).
    std::vector<bodyID_t> ownerUserToInternal, ownerInternalToUser;
    std::vector<bodyID_t> sphereInternalToUser, sphereUserToInternal;
    // The sphere maps equal the owners' over the spheres and are not kept (state/SphereIds.h, which
    // every reader of them goes through); userSphereIds is then how many sphere ids were issued.
    bool sphereIdsAreOwnerIds = false;
    size_t userSphereIds = 0;
    // Owners and spheres can be removed during a run (runtime/SceneEdits.h): their user ids stay
    // taken, mapped to REMOVED_ID, so the ids of the others never change.
    static constexpr bodyID_t REMOVED_ID = ~bodyID_t(0);
    MaterialTables materials;
    WildcardArrays wildcards;
    unsigned int numWildcards = 0;
    size_t numClumps = 0;  // owners [0, numClumps) are clumps; analytical owners, then meshes follow
    size_t numAnalyticalOwners = 0;
    // Clumps removed since Initialize (RemoveClumpsInFamily, the "remove" domain exit policy) and
    // their total mass.
    size_t numRemovedClumps = 0;
    double removedMass = 0.0;
    // First geometry id of each kind in the unified id space of contacts.
    bodyID_t analyticalIdBase() const { return (bodyID_t)spheres.size(); }
    bodyID_t triangleIdBase() const { return (bodyID_t)(spheres.size() + analytical.size()); }
};

// Pair i's A, for the per-pair code written once for both backends (a GPU view's: state/StateView.h).
// The CPU's per-pair readers run where geomA is held (a set keeping A as runs passes A itself:
// dynamics/ContactStep.h, contactIdsWithA).
inline bodyID_t pairAOf(const SimState& s, size_t i) { return s.contacts.geomA[i]; }

}  // namespace deme
