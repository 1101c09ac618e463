#include "backend/cuda/DeviceState.h"

#include <algorithm>
#include <type_traits>

namespace deme::cuda {

namespace {

// Copies by role (state/StateFields.h): what the host writes goes up, what the steps write comes
// back; the steps' scratch is sized where they run; the CPU's bookkeeping stays on the host; the
// steps' results go up where the host has them and come back only when asked for.
struct Upload {
    Stream stream;
    size_t numOwners;
    template <class T>
    void operator()(DeviceBuffer<T>& d, const std::vector<T>& h, FieldRole role) const {
        if (role == FieldRole::HOST) return;
        const bool hostHasNone = role == FieldRole::RESULT && h.size() != numOwners;
        if (role == FieldRole::SCRATCH || hostHasNone) {
            // Results the host lets go (state/SimState.h) stay as the steps left them, one per owner
            // (an edit that renumbers owners sends the host's: Simulation::wholeState); a new
            // scene's start at zero. Scratch is cleared, not left as the memory was: the force pass
            // reads an owner's step flags (a parked clump touches nothing, dynamics/ContactStep.h)
            // before the first step writes them.
            if (hostHasNone && d.size() == numOwners) return;
            d.resizeDiscarding(numOwners);
            if (numOwners) d.zeroAsync(stream);
            return;
        }
        uploadResized(d, h, stream);
    }
};

// Brings back the fields of one role (each one per owner).
struct Download {
    Stream stream;
    FieldRole which;
    template <class T>
    void operator()(const DeviceBuffer<T>& d, std::vector<T>& h, FieldRole role) const {
        if (role != which) return;
        h.resize(d.size());
        if (!h.empty()) d.downloadAsync(h.data(), h.size(), stream);
    }
};

// Elements of contact field `field` (a member of `c`) for n pairs: W for the wildcards, one for every
// other field.
template <class V>
size_t contactFieldCount(const ContactArrays& c, const V& field, size_t n, unsigned int W) {
    return static_cast<const void*>(&field) == static_cast<const void*>(&c.wildcards) ? n * W : n;
}

struct Point {
    template <class T>
    void operator()(T*& v, DeviceBuffer<T>& d, FieldRole role) const {
        v = role == FieldRole::HOST ? nullptr : d.data();
    }
};

}  // namespace

void DeviceState::upload(const SimState& s, Stream stream) {
    const Upload up{stream, s.owners.size()};
    {
        const MemoryGroupScope group(MemoryGroup::OWNER_STATE);
        forEachOwnerField(owners, s.owners, up);
        forEachTrackerLoadField(trackerLoads, s.trackerLoads, up);
        forEachMassField(massProps, s.massProps, up);
        forEachScratchField(integrationScratch, s.integrationScratch, up);
    }
    // The cache's placed positions are geometry (its two owner arrays, small beside them, too).
    const MemoryGroupScope group(MemoryGroup::GEOMETRY);
    forEachSphereField(spheres, s.spheres, up);
    forEachAnalyticalField(analytical, s.analytical, up);
    forEachTriangleField(triangles, s.triangles, up);
    forEachCacheField(cache, s.cache, up);
    // Spheres that are their owners keep no offsets, centres or arms (state/SphereLayout.h): no
    // storage either, where an earlier layout had some.
    if (s.spheresAreOwners) {
        spheres.relPos.release();
        cache.spherePos.release();
        cache.sphereArm.release();
    }
}

void DeviceState::uploadTrackerLoads(const SimState& s, Stream stream) {
    const MemoryGroupScope group(MemoryGroup::OWNER_STATE);
    forEachTrackerLoadField(trackerLoads, s.trackerLoads, Upload{stream, 0});
}

void DeviceState::download(SimState& s, Stream stream) const {
    const Download down{stream, FieldRole::EVOLVES};
    forEachOwnerField(owners, s.owners, down);
    forEachCacheField(cache, s.cache, down);
}

void DeviceState::downloadResults(SimState& s, Stream stream) const {
    forEachOwnerField(owners, s.owners, Download{stream, FieldRole::RESULT});
}

void DeviceState::viewInto(StateView& v) {
    const Point point;
    forEachOwnerField(v.owners, owners, point);
    forEachMassField(v.massProps, massProps, point);
    forEachSphereField(v.spheres, spheres, point);
    forEachAnalyticalField(v.analytical, analytical, point);
    forEachTriangleField(v.triangles, triangles, point);
    forEachCacheField(v.cache, cache, point);
    forEachScratchField(v.integrationScratch, integrationScratch, point);
}

void uploadContacts(const ContactArrays& c, unsigned int W, DeviceContacts& d, Stream stream, bool flagsKept) {
    const size_t n = c.size();
    forEachContactField(d, c, [&](auto& dev, const auto& host, FieldRole role) {
        if (role != FieldRole::EVOLVES) return;
        if (static_cast<const void*>(&host) == &c.geomA) {
            uploadPairAs(c.geomA, d.pairA, stream);  // compact on the device
            return;
        }
        // A set with no flag set and a model that sets none keeps no flags (as the CPU's).
        if (static_cast<const void*>(&host) == &c.persistent && !flagsKept &&
            std::none_of(c.persistent.begin(), c.persistent.end(), [](uint8_t f) { return f != 0; })) {
            dev.release();
            return;
        }
        // Per-pair fields the host has not filled yet (none persistent, no forces) start at zero.
        const size_t count = contactFieldCount(c, host, n, W);
        dev.resizeDiscarding(count);
        if (host.size() == count && count)
            dev.uploadAsync(host.data(), count, stream);
        else if (count)
            dev.zeroAsync(stream);
    });
}

void downloadContacts(const DeviceContacts& d, size_t n, unsigned int W, ContactArrays& c, Stream stream,
                      bool historyAndForces) {
    forEachContactField(d, c, [&](const auto& dev, auto& host, FieldRole role) {
        // The CPU's bookkeeping (its per-owner index, per-contact torques) has no device copy: the
        // GPU adds loads to the owners directly. Left empty, it costs the host nothing.
        if (role == FieldRole::HOST) return;
        if (static_cast<const void*>(&host) == &c.geomA) {
            downloadPairAs(d.pairA, n, c.geomA, stream);  // whole on the host
            return;
        }
        if (!historyAndForces &&
            (static_cast<const void*>(&host) == &c.wildcards || static_cast<const void*>(&host) == &c.force))
            return;
        const size_t count = contactFieldCount(c, host, n, W);
        host.resize(count);
        // Per-contact forces exist only after a storing step of the set in use (CudaDynamics::
        // lendIdleMemoryToForces); before one (a set just installed, and a call that failed before its
        // last step) they read as none.
        if (dev.size() < count) {
            std::fill(host.begin(), host.end(), std::decay_t<decltype(host[0])>{});
            return;
        }
        if (count) dev.downloadAsync(host.data(), count, stream);
    });
}

void viewContacts(DeviceContacts& d, size_t n, StateView& v) {
    forEachContactField(v.contacts, d, Point{});
    v.pairAs = d.pairA.view();
    v.numContacts = n;
}

}  // namespace deme::cuda
