#include "runtime/MemoryAccounting.h"

#include "runtime/Simulation.h"

namespace deme {

const char* memoryGroupName(MemoryGroup g) {
    static const char* names[NUM_MEMORY_GROUPS] = {"owner state", "geometry",          "contacts and history",
                                                   "wildcards",   "detection scratch", "output staging",
                                                   "step scratch"};
    return names[(int)g];
}

const char* memoryGroupKey(MemoryGroup g) {
    static const char* keys[NUM_MEMORY_GROUPS] = {"owner_state", "geometry",          "contacts_and_history",
                                                  "wildcards",   "detection_scratch", "output_staging",
                                                  "step_scratch"};
    return keys[(int)g];
}

namespace {

// f over every array of a field group, counted to group g.
struct CountTo {
    MemoryStats& m;
    MemoryGroup g;
    template <class V>
    void operator()(const V& v, const V&, FieldRole) const {
        addHost(m, g, vectorBytes(v));
    }
};

}  // namespace

void countStateMemory(const SimState& s, MemoryStats& m) {
    const CountTo owners{m, MemoryGroup::OWNER_STATE}, geometry{m, MemoryGroup::GEOMETRY};
    forEachOwnerField(s.owners, s.owners, owners);
    forEachTrackerLoadField(s.trackerLoads, s.trackerLoads, owners);
    forEachMassField(s.massProps, s.massProps, owners);
    forEachScratchField(s.integrationScratch, s.integrationScratch, owners);
    forEachSphereField(s.spheres, s.spheres, geometry);
    forEachAnalyticalField(s.analytical, s.analytical, geometry);
    forEachTriangleField(s.triangles, s.triangles, geometry);
    forEachCacheField(s.cache, s.cache, geometry);
    // The per-contact wildcards are the contacts' history (MemoryGroup::CONTACTS).
    forEachContactField(s.contacts, s.contacts, [&](const auto& v, const auto&, FieldRole) {
        addHost(m, MemoryGroup::CONTACTS, vectorBytes(v));
    });
    addHost(m, MemoryGroup::CONTACTS, s.contacts.pooled.bytes());
    for (const std::vector<uint32_t>& v : s.contacts.stored.index) addHost(m, MemoryGroup::CONTACTS, vectorBytes(v));
    for (const std::vector<float3>& v : s.contacts.stored.force) addHost(m, MemoryGroup::CONTACTS, vectorBytes(v));
    for (const std::vector<float>& w : s.wildcards.owner) addHost(m, MemoryGroup::WILDCARDS, vectorBytes(w));
    for (const std::vector<float>& w : s.wildcards.geometry) addHost(m, MemoryGroup::WILDCARDS, vectorBytes(w));
    addHost(m, MemoryGroup::OWNER_STATE, vectorBytes(s.ownerUserToInternal) + vectorBytes(s.ownerInternalToUser));
    addHost(
        m, MemoryGroup::GEOMETRY,
        vectorBytes(s.ownerSphereStart) + vectorBytes(s.sphereInternalToUser) + vectorBytes(s.sphereUserToInternal));
}

MemoryStats Simulation::hostMemory() const {
    MemoryStats m;
    countStateMemory(m_state, m);
    if (m_backends.dynamics) m_backends.dynamics->countHostMemory(m);
    if (m_backends.kinematics) m_backends.kinematics->countHostMemory(m);
    m.spheres = m_state.spheres.size();
    for (int g = 0; g < NUM_MEMORY_GROUPS; g++) m.estimatedBytes[g] = m_memoryEstimate.bytes[g];
    m.estimatedPairs = m_memoryEstimate.pairs;
    return m;
}

}  // namespace deme
