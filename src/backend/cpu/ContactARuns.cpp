#include "backend/cpu/ContactARuns.h"

#include <cstdlib>
#include <cstring>

#include "parallel/Parallel.h"
#include "runtime/MemoryAccounting.h"

namespace deme {

bool contactAAsRunsAllowed(const SimState& s) {
    if (!s.spheresAreOwners) return false;
    const char* v = std::getenv("DEME_CONTACT_A_PER_PAIR");
    return !(v && *v && std::strcmp(v, "0") != 0);
}

namespace {

// Whether pair i's A is the owner whose run holds i, for every pair.
bool runsGiveA(const ContactArrays& c, size_t nOwners) {
    if (c.ownerAStart.size() != nOwners + 1 || c.ownerAStart.back() != c.size() || c.geomA.size() != c.size())
        return false;
    int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad) if (nOwners > PARALLEL_MIN_ITEMS)
    for (long o = 0; o < (long)nOwners; o++)
        for (uint32_t i = c.ownerAStart[o]; i < c.ownerAStart[o + 1]; i++) bad |= c.geomA[i] != (bodyID_t)o;
    return bad == 0;
}

}  // namespace

bool keepContactAAsRuns(SimState& s, bool indexFresh) {
    ContactArrays& c = s.contacts;
    if (c.aAsRuns) return true;
    if (c.size() == 0 || !contactAAsRunsAllowed(s)) return false;
    if (!indexFresh && !runsGiveA(c, s.owners.size())) return false;
    releaseVector(c.geomA);
    c.aAsRuns = true;
    return true;
}

}  // namespace deme
