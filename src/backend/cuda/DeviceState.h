// The simulation state in device memory: the field lists of state/StateFields.h as device buffers,
// and their copies to and from the host's SimState, made from the fields' roles (INPUT and EVOLVES
// fields go up, EVOLVES fields come back, SCRATCH fields are sized per owner, HOST fields stay on
// the host, RESULT fields go up where the host has them and come back when asked for). Contact sets are kept by the
// dynamics side itself (two of them, for history mapping), with the contact field list: DeviceContacts.
#pragma once

#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DevicePairA.h"
#include "state/SimState.h"
#include "state/StateView.h"

namespace deme::cuda {

// A set's A ids are kept compact (backend/cuda/DevicePairA.h): its field geomA stays empty on the
// device, and its view reads A through StateView::pairAs.
struct DeviceContacts : ContactFields<DeviceBuffer> {
    DevicePairA pairA;
};

struct DeviceState {
    OwnerFields<DeviceBuffer> owners;
    // Sized to the owners while a call has tracker loads, else empty; their storage is kept once
    // made, so a run that adds loads call after call allocates it once.
    TrackerLoadFields<DeviceBuffer> trackerLoads;
    MassFields<DeviceBuffer> massProps;
    SphereFields<DeviceBuffer> spheres;
    AnalyticalFields<DeviceBuffer> analytical;
    TriangleFields<DeviceBuffer> triangles;
    CacheFields<DeviceBuffer> cache;
    ScratchFields<DeviceBuffer> integrationScratch;

    // Queues the copies of every uploaded field of `s` on `stream` (the host arrays must stay as
    // they are until the stream has passed them).
    void upload(const SimState& s, Stream stream);
    // Queues the copies of every evolving field into `s` on `stream`.
    void download(SimState& s, Stream stream) const;
    // The same of the owners' results (state/SimState.h; as many as the device has).
    void downloadResults(SimState& s, Stream stream) const;
    // Sends the host's tracker loads (none: the steps read none).
    void uploadTrackerLoads(const SimState& s, Stream stream);
    // Points `v`'s arrays (all but its contacts) at these buffers.
    void viewInto(StateView& v);
};

// The contact set `c` of the host (n pairs, W wildcards each) onto the device, and back. A set whose
// host copy has no persistent flag set keeps no flags on the device unless `flagsKept` (the model
// may set them); one without them downloads a flag of 0 per pair (the host's readers' form).
void uploadContacts(const ContactArrays& c, unsigned int W, DeviceContacts& d, Stream stream, bool flagsKept);
// `historyAndForces` false: the wildcards and per-contact forces are left to the caller (a pooled
// history keeps them per slot: CudaDynamics::downloadPooledHistory).
void downloadContacts(const DeviceContacts& d, size_t n, unsigned int W, ContactArrays& c, Stream stream,
                      bool historyAndForces = true);
// Points the view's contact arrays at `d`'s (n pairs).
void viewContacts(DeviceContacts& d, size_t n, StateView& v);

}  // namespace deme::cuda
