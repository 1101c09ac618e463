// Kernels of the exchange between the dynamics side (dT) and the kinematics side (kT) on the GPU:
// whether a contact set that kT delivers may still serve, i.e. how far the owners travelled since
// the snapshot it was detected from. Compiled at run time by NVRTC, loaded on dT's GPU.
#include <deme/VariableTypes.h>

namespace deme {

// *maxBits = max(*maxBits, bits of max_o (travel[o] - baseline[o])): travel only grows, so the
// differences are non-negative doubles, whose bits order like the values. Zero *maxBits first.
extern "C" __global__ void deme_max_travel_since(const double* travel, const double* baseline, unsigned int n,
                                                 unsigned long long* maxBits) {
    const size_t o = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (o >= n) return;
    const double d = fmax(travel[o] - baseline[o], 0.0);
    atomicMax(maxBits, (unsigned long long)__double_as_longlong(d));
}

}  // namespace deme
