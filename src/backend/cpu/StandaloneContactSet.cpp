#include "backend/cpu/StandaloneContactSet.h"

#include "backend/cpu/ContactDetector.h"
#include "backend/cpu/HistoryMapping.h"
#include "dynamics/KinematicCache.h"
#include "kinematics/BinGridSizing.h"
#include "runtime/FamilyRules.h"

namespace deme {

void detectAndInstallContacts(SimState& s, double margin) {
    refreshKinematicCache(s);
    const BinGrid grid = makeBinGrid(s, 0.0);
    FamilyRules families;
    const float extra[NUM_FAMILIES] = {};
    ContactDetector detector;
    DetectedContacts pairs;
    double binning = 0.0, search = 0.0;
    detector.detect(s, grid, margin, families.contactMask(), extra, pairs, binning, search);
    installDetectedContacts(s, pairs, true);  // (every flag kept: the caller reads the set as a host reader)
}

}  // namespace deme
