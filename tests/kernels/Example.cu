// A test-only kernel compiled at run time by NVRTC (src/backend/cuda/NvrtcCompiler.h): it includes
// the single-source physics headers exactly as the engine's kernels do. The smallest case for the
// NVRTC and launch tests (test_cuda_plumbing.cpp, test_cuda_gpu.cpp), which run it on a GPU against
// the host; read from the source tree by tests/TestKernels.h, never embedded in the library.
#include "physics/ContactGeometry.h"
#include "physics/Quaternion.h"

// One thread per sphere pair (i, i + 1): the overlap of the two spheres, and the normal rotated into
// the first sphere's local frame by its orientation.
extern "C" __global__ void exampleSpherePairOverlap(const deme::double3* pos, const float* radius,
                                                    const deme::float4* oriQ, double* overlap,
                                                    deme::float3* localNormal, unsigned int numPairs) {
    const unsigned int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= numPairs) return;
    const deme::ContactPoint c = deme::sphereSphereContact(pos[i], radius[i], pos[i + 1], radius[i + 1]);
    overlap[i] = c.overlap;
    localNormal[i] = deme::rotateToLocal(oriQ[i], c.B2A);
}
