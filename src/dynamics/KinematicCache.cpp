#include "dynamics/KinematicCache.h"

#include "dynamics/ContactInputsGather.h"
#include "dynamics/OwnerStep.h"
#include "parallel/Parallel.h"

namespace deme {

void updateAnalyticalCache(SimState& s) {
    // The pose only: the speed bound it also returns is the steps' business.
    for (size_t c = 0; c < s.analytical.size(); c++) placeAnalytical(s, c, 0.0);
}

void refreshKinematicCache(SimState& s) {
    KinematicCache& k = s.cache;
    const size_t nT = s.triangles.size();
    // Spheres that are their owners have no centres or arms of their own (state/SphereLayout.h).
    const size_t nS = s.spheresAreOwners ? 0 : s.spheres.size();
    k.spherePos.resize(nS);
    k.sphereArm.resize(nS);
    k.analPos.resize(s.analytical.size());
    k.analDir.resize(s.analytical.size());
    k.triVert.resize(3 * nT);
#pragma omp parallel if (nS + nT > PARALLEL_MIN_ITEMS)
    {
#pragma omp for schedule(static)
        for (size_t i = 0; i < nS; i++) placeSphere(s, i);
#pragma omp for schedule(static)
        for (size_t t = 0; t < nT; t++) placeTriangle(s, t);
    }
    updateAnalyticalCache(s);
}

}  // namespace deme
