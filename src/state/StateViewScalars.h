// A StateView's (state/StateView.h) scalars and counts from the host state: what the GPU's view
// takes at an upload (CudaDynamics::upload) and the host-run kernel tests' views take alike.
#pragma once

#include "state/SimState.h"
#include "state/StateView.h"

namespace deme {

// The view's frame, domain, wildcard count, sphere layout and item counts from `s` (not the
// contacts': a device set's size is the backend's).
inline void setViewScalars(StateView& v, const SimState& s) {
    v.frame = s.frame;
    v.domainSize = s.domainSize;
    v.numWildcards = s.numWildcards;
    v.spheresAreOwners = s.spheresAreOwners;
    v.voxelPretest = false;  // the GPU's dynamics sets it for each set it installs (CudaDynamics::refreshView)
    v.numOwners = (uint32_t)s.owners.size();
    v.numSpheres = (uint32_t)s.spheres.size();
    v.numAnalytical = (uint32_t)s.analytical.size();
    v.numTriangles = (uint32_t)s.triangles.size();
    v.numClumps = (uint32_t)s.numClumps;
    v.numAnalyticalOwners = (uint32_t)s.numAnalyticalOwners;
}

}  // namespace deme
