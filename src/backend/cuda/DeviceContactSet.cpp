#include "backend/cuda/DeviceContactSet.h"

namespace deme::cuda {

void mapContactHistory(const CudaKernel& kMapHistory, const DeviceContacts& old, uint32_t numOld,
                       DeviceContacts& fresh, uint32_t numFresh, unsigned int W, Stream stream) {
    constexpr unsigned int THREADS = 256;
    if (!numFresh) return;
    launch(kMapHistory, blocksFor(numFresh, THREADS), THREADS, 0, stream, fresh.geomA.data(), fresh.geomB.data(),
           (unsigned int)numFresh, old.geomA.data(), old.geomB.data(), (unsigned int)numOld, old.wildcards.data(),
           old.meshState.data(), W, fresh.wildcards.data(), fresh.meshState.data());
}

}  // namespace deme::cuda
