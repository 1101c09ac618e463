#include "dynamics/KinematicCache.h"

#include "parallel/Parallel.h"
#include "dynamics/OwnerStep.h"

namespace deme {

void updateAnalyticalCache(SimState& s) {
    for (size_t c = 0; c < s.analytical.size(); c++) placeAnalytical(s, c);
}

void refreshKinematicCache(SimState& s) {
    KinematicCache& k = s.cache;
    const size_t n = s.owners.size();
    k.ownerPos.resize(n);
    k.ownerAngVelGlobal.resize(n);
    k.spherePos.resize(s.spheres.size());
    k.sphereArm.resize(s.spheres.size());
    k.analPos.resize(s.analytical.size());
    k.analDir.resize(s.analytical.size());
    k.triVert.resize(3 * s.triangles.size());
#pragma omp parallel for schedule(static) if (n > PARALLEL_MIN_ITEMS)
    for (size_t o = 0; o < n; o++) updateOwnerCache(s, o);
    updateAnalyticalCache(s);
}

}  // namespace deme
