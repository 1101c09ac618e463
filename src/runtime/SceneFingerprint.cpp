#include "runtime/SceneFingerprint.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <type_traits>

#include "state/OwnerTypeOf.h"

namespace deme {

constexpr uint64_t FNV_PRIME = 1099511628211ull;

uint64_t fnv1aAfterZeroBytes(uint64_t h, uint64_t count) {
    uint64_t power = 1, p = FNV_PRIME;
    for (; count; count >>= 1, p *= p)
        if (count & 1) power *= p;
    return h * power;
}

namespace {

// 64-bit FNV-1a (offset basis and prime from the FNV reference); each part's length goes in before
// its bytes, so that ("ab", "c") and ("a", "bc") differ.
class Hash {
  public:
    void bytes(const void* p, size_t n) {
        const unsigned char* b = static_cast<const unsigned char*>(p);
        for (size_t i = 0; i < n; i++) {
            m_h ^= b[i];
            m_h *= FNV_PRIME;
        }
    }
    void zeroBytes(uint64_t n) { m_h = fnv1aAfterZeroBytes(m_h, n); }
    template <class T>
    void value(const T& v) {
        static_assert(std::is_trivially_copyable<T>::value, "plain values only");
        bytes(&v, sizeof(T));
    }
    template <class T>
    void array(const std::vector<T>& v) {
        value((uint64_t)v.size());
        if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
    }
    void text(const std::string& s) {
        value((uint64_t)s.size());
        bytes(s.data(), s.size());
    }
    // What array() hashes for the per-owner ranges of items sorted by owner (rangesByOwner's: item
    // counts summed, n + 1 starts) without making them: the few owners with items are counted.
    void ownerRanges(size_t n, const std::vector<bodyID_t>& ownerOf) {
        std::map<bodyID_t, uint32_t> count;
        for (bodyID_t o : ownerOf) count[o]++;
        value((uint64_t)(n + 1));
        uint32_t start = 0;
        auto next = count.begin();
        for (size_t o = 0; o <= n; o++) {
            value(start);
            if (next != count.end() && next->first == o) start += (next++)->second;
        }
    }
    // What array() hashes for the per-owner sphere ranges where spheres are their owners (owner o's
    // sphere is sphere o; the owners after the clumps have none: ownerSphereRanges), without making
    // them.
    void ownSphereRanges(size_t numOwners, size_t numSpheres) {
        value((uint64_t)(numOwners + 1));
        for (size_t o = 0; o <= numOwners; o++) value((uint32_t)std::min(o, numSpheres));
    }
    uint64_t result() const { return m_h; }

  private:
    uint64_t m_h = 14695981039346656037ull;
};

// Every INPUT field of a group, in list order.
template <class Visit, class G>
uint64_t hashInputs(Visit&& visit, const G& group, Hash h = Hash()) {
    visit(group, group, [&](const auto& field, const auto&, FieldRole role) {
        if (role == FieldRole::INPUT) h.array(field);
    });
    return h.result();
}

// The spheres' INPUT fields as the full layout holds them: where spheres are their owners the state
// keeps no owners (sphere i's is owner i) and no offsets (zero), and these are hashed as the arrays
// they stand for, so that a scene's fingerprint does not depend on its layout (checkpoints of either
// read in the other; test SceneAssembly.OneSphereClumpsAreTheirOwnersFromTheStart).
uint64_t hashSphereInputs(const SimState& s) {
    Hash h;
    const size_t n = s.spheres.size();
    forEachSphereField(s.spheres, s.spheres, [&](const auto& field, const auto&, FieldRole role) {
        if (role != FieldRole::INPUT) return;
        using T = typename std::decay_t<decltype(field)>::value_type;
        if (!s.spheresAreOwners || field.size() == n) return h.array(field);
        h.value((uint64_t)n);
        if constexpr (std::is_same_v<T, bodyID_t>) {
            for (size_t i = 0; i < n; i++) h.value((bodyID_t)i);  // the owners
        } else if constexpr (std::is_same_v<T, float3>) {
            h.zeroBytes((uint64_t)n * sizeof(T));  // the offsets: +0, every byte zero, as one run
        } else {
            for (size_t i = 0; i < n; i++) h.value(T{});
        }
    });
    return h.result();
}

}  // namespace

SceneFingerprint sceneFingerprint(const SimState& s, const ModelLayout& model) {
    SceneFingerprint fp;
    fp.owners = s.owners.size();
    fp.clumps = s.numClumps;
    fp.analyticalOwners = s.numAnalyticalOwners;
    fp.spheres = s.spheres.size();
    fp.analytical = s.analytical.size();
    fp.triangles = s.triangles.size();
    fp.templates = s.massProps.mass.size();
    fp.materials = s.materials.count;
    // (A flag per family number: a set of them took a tree search per owner.)
    static_assert(sizeof(family_t) == 1, "a flag per family number");
    bool used[256] = {};
    for (family_t f : s.owners.family) used[f] = true;
    fp.families = (uint64_t)std::count(std::begin(used), std::end(used), true);
    fp.contactWildcards = s.numWildcards;
    fp.ownerWildcards = s.wildcards.owner.size();
    fp.geometryWildcards = s.wildcards.geometry.size();

    // The generic lambdas below take the group's two storages (the same one twice here).
    auto owners = [](const auto& a, const auto& b, auto&& f) { forEachOwnerField(a, b, f); };
    auto mass = [](const auto& a, const auto& b, auto&& f) { forEachMassField(a, b, f); };
    auto anal = [](const auto& a, const auto& b, auto&& f) { forEachAnalyticalField(a, b, f); };
    auto tris = [](const auto& a, const auto& b, auto&& f) { forEachTriangleField(a, b, f); };
    // The owners' types stood first among their INPUT fields until they were derived (2026-12-07,
    // state/OwnerTypeOf.h): hashed as that array, so that checkpoints written before still match.
    Hash ownerHash;
    ownerHash.value((uint64_t)s.owners.size());
    // (The clumps' bytes, OWNER_CLUMP = 0, as one run: fnv1aAfterZeroBytes.)
    static_assert(OWNER_CLUMP == 0 && sizeof(ownerTypeOf(s, 0)) == 1, "a clump's type is a zero byte");
    const size_t clumps = std::min((size_t)s.numClumps, s.owners.size());
    ownerHash.zeroBytes(clumps);
    for (size_t o = clumps; o < s.owners.size(); o++) ownerHash.value(ownerTypeOf(s, o));
    fp.ownerInputs = hashInputs(owners, s.owners, ownerHash);
    fp.templateInputs = hashInputs(mass, s.massProps);
    Hash g;
    g.value(hashSphereInputs(s));
    g.value(hashInputs(anal, s.analytical));
    g.value(hashInputs(tris, s.triangles));
    if (s.spheresAreOwners && s.ownerSphereStart.empty())
        g.ownSphereRanges(s.owners.size(), s.spheres.size());
    else
        g.array(s.ownerSphereStart);
    g.ownerRanges(s.owners.size(), s.triangles.owner);  // (as the triangle ranges once kept were hashed)
    fp.geometryInputs = g.result();

    Hash m;
    const MaterialTables& mt = s.materials;
    m.value(mt.count);
    for (const auto* v : {&mt.E, &mt.nu, &mt.CoR, &mt.mu, &mt.Crr}) m.array(*v);
    for (const auto& v : mt.props) m.array(v);
    for (const auto& v : mt.pairProps) m.array(v);
    fp.materialInputs = m.result();

    Hash d;
    d.value(s.frame.origin);
    d.value(s.frame.voxelSize);
    d.value(s.domainSize);
    if (s.frame.periodic.axes) d.value(s.frame.periodic.axes);  // (so non-periodic scenes hash as before)
    if (s.frame.periodic.shear) d.value(s.frame.periodic.shearVelocity);
    fp.domain = d.result();

    Hash f;
    f.value((int)model.kind);
    f.text(model.source);
    for (const auto* list : {&model.materialProps, &model.pairProps, &model.contactWildcards, &model.ownerWildcards,
                             &model.geometryWildcards}) {
        f.value((uint64_t)list->size());
        for (const auto& name : *list) f.text(name);
    }
    // A custom model not called for apart pairs sees fewer pairs (the default, called, hashes as
    // before, so that checkpoints written before the setting existed still read).
    if (!model.builtIn() && !model.calledForApartPairs) f.text("not called for apart pairs");
    fp.model = f.result();
    return fp;
}

std::string fingerprintMismatch(const SceneFingerprint& checkpoint, const SceneFingerprint& mine) {
    SceneFingerprint a = checkpoint, b = mine;
    std::string out;
    // Walks both in step: the same fields in the same order.
    std::vector<std::pair<const char*, uint64_t>> theirs;
    forEachFingerprintField(a, [&](const char* name, uint64_t& v, bool) { theirs.emplace_back(name, v); });
    size_t i = 0;
    forEachFingerprintField(b, [&](const char* name, uint64_t& v, bool isCount) {
        const uint64_t t = theirs[i++].second;
        if (!out.empty() || t == v) return;
        // A hash only says that the two differ.
        if (isCount)
            out = std::to_string(t) + " " + name + " in the checkpoint's scene, " + std::to_string(v) + " in this one";
        else
            out = "the " + std::string(name) + " differ";
    });
    return out;
}

}  // namespace deme
