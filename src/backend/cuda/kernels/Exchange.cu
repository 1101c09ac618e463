// Kernels of the exchange between the dynamics side (dT) and the kinematics side (kT) on the GPU:
// whether a contact set that kT delivers may still serve, i.e. how far the owners travelled since
// the snapshot it was detected from. Compiled at run time by NVRTC, loaded on dT's GPU.
#include <deme/VariableTypes.h>

#include "dynamics/TravelSinceSnapshot.h"

namespace deme {

// *maxBits = max(*maxBits, bits of max_o travelSinceOrderSnapshot(travel[o], atOrder[o])): the
// differences are non-negative, and a non-negative double's bits order like its value. Zero
// *maxBits first.
extern "C" __global__ void deme_max_travel_since(const float* travel, const float* atOrder, unsigned int n,
                                                 unsigned long long* maxBits) {
    const size_t o = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (o >= n) return;
    const double d = (double)travelSinceOrderSnapshot(travel[o], atOrder[o]);
    atomicMax(maxBits, (unsigned long long)__double_as_longlong(d));
}

// The order's set installed: every owner's travel counts from the order's snapshot.
extern "C" __global__ void deme_travel_since_order(float* travel, const float* atOrder, unsigned int n) {
    const size_t o = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (o >= n) return;
    travel[o] = travelSinceOrderSnapshot(travel[o], atOrder[o]);
}

}  // namespace deme
