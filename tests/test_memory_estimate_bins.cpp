// The memory estimate's detection bins (runtime/MemoryEstimate.h) follow how the backend registers
// the spheres: by centre where it does and the rule allows (kinematics/DetectionRules.h).
#include <gtest/gtest.h>

#include <algorithm>

#include "DetectionScenes.h"
#include "kinematics/BinGridSizing.h"
#include "runtime/HistoryPoolPolicy.h"
#include "runtime/MemoryEstimate.h"
#include "state/CompactPairA.h"

using namespace deme;
using namespace deme_test;

// The detection's bins as the backend registers the spheres (KinematicsBackend::
// mayBinSpheresByCentre): by centre one entry a sphere where the rule allows (bins of 4 mm for radii
// up to 2 mm), so exactly 4 bytes for each entry a box registration would make beyond the first;
// where the rule does not allow it (bins of 1.5 mm) the backend's answer changes nothing.
TEST(MemoryEstimateBins, SpheresByCentreAreOneEntryEachWhereTheBackendBinsSo) {
    const Scene scene = randomScene(3, 1500);
    SimState s = detectionState(scene, "MemoryEstimateBins");
    const size_t det = (size_t)MemoryGroup::DETECTION;
    for (bool onGpu : {false, true}) {
        const BinGrid coarse = makeBinGrid(s, 0.004), fine = makeBinGrid(s, 0.0015);
        const size_t centre = estimateRunMemory(s, coarse, onGpu, true).bytes[det];
        const size_t boxes = estimateRunMemory(s, coarse, onGpu, false).bytes[det];
        EXPECT_GT(boxes, centre + 4 * s.spheres.size()) << "on the GPU: " << onGpu;
        EXPECT_EQ(estimateRunMemory(s, fine, onGpu, true).bytes[det],
                  estimateRunMemory(s, fine, onGpu, false).bytes[det])
            << "on the GPU: " << onGpu;
    }
}

// A synchronous detection in place on the GPU runs while the set in use holds only the pairs it kept
// (trimmed before it), and a large scratch is let go before the installation: the run's peak is the
// larger of the trim's or installation's (the whole set of ids -- B, and A in a byte a pair and a
// base per 32 pairs --, its slots' bits and ranks, 20 B per 64 pairs, and the trim's marks, 12 B per
// 64 pairs, beside the kept pairs) and the detection's (its offsets and the outbox's B, with its bins
// while it fills, then with A compact and its rows, as the bins go first), not their sum. Measured on
// an H100 at 45.8 M spheres (BENCHMARKS.md, MEMORY): a peak of 175.5 device B/sphere where the sum
// counted 208.7.
TEST(MemoryEstimateBins, ADetectionInPlaceCountsWhatItHoldsBeyondTheWholeSet) {
    const Scene scene = randomScene(3, 1500);
    SimState s = detectionState(scene, "MemoryEstimateBins");
    s.numWildcards = 4;  // Hertz-Mindlin's history, pooled
    const BinGrid grid = makeBinGrid(s, 0.004);
    const size_t det = (size_t)MemoryGroup::DETECTION, con = (size_t)MemoryGroup::CONTACTS;
    ContactSetForm trimmed;
    trimmed.historySlots = 0;  // a first set: no pair has a history yet
    trimmed.trimmedBeforeDetection = true;
    trimmed.persistentFlags = false;
    ContactSetForm whole = trimmed;
    whole.trimmedBeforeDetection = false;
    for (size_t pairs : {(size_t)6 * s.spheres.size(), s.spheres.size() / 4}) {
        SCOPED_TRACE("pairs " + std::to_string(pairs));
        auto estimate = [&](const ContactSetForm& form, bool snapshotKept, size_t keptUpTo) {
            return estimateRunMemory(
                s, grid, true, true, snapshotKept, pairs, [&](size_t) { return form; }, keptUpTo);
        };
        const MemoryEstimate kept = estimate(trimmed, false, SIZE_MAX), released = estimate(trimmed, false, 0);
        EXPECT_EQ(released.bytes[con], kept.bytes[con]);
        const size_t offsets = s.spheres.size() * sizeof(PairOffset);
        const size_t bins = kept.bytes[det] - offsets;  // (no triangles, no snapshot)
        const size_t bases = (pairs + 31) / 32 * 4, compactA = pairs + bases, rows = bases;
        // (the ids; the mesh states are per slot)
        const size_t wholeSet = pairs * sizeof(bodyID_t) + compactA + (pairs + 63) / 64 * (20 + 12);
        const size_t detecting = offsets + pairs * sizeof(bodyID_t) + std::max(bins, compactA + rows);
        EXPECT_EQ(released.bytes[det], detecting > wholeSet ? detecting - wholeSet : 0);
        EXPECT_LT(released.total(), kept.total());
        // Nothing changes where a snapshot is kept, where the scratch is kept, or where the set is
        // not trimmed (two sets are held at an installation).
        EXPECT_EQ(estimate(trimmed, true, 0).bytes[det], estimate(trimmed, true, SIZE_MAX).bytes[det]);
        EXPECT_EQ(estimate(whole, false, 0).bytes[det], estimate(whole, false, SIZE_MAX).bytes[det]);
        EXPECT_EQ(kept.bytes[det], estimate(whole, false, SIZE_MAX).bytes[det]);
    }
}

// A pooled GPU set's late tables (state/HistoryPool.h) are counted for the spare slots its pools keep
// (ContactSetForm::lateSlots): at an installation the old pool's and the fresh one's, each a power of
// two at least twice those slots (lateTableEntriesFor), 8 bytes an entry; nothing else changes. The
// CPU keeps no late table.
TEST(MemoryEstimateBins, APooledGpuSetCountsALateTableForEachPoolsSpareSlots) {
    const Scene scene = randomScene(3, 1500);
    SimState s = detectionState(scene, "MemoryEstimateBins");
    s.numWildcards = 4;
    const size_t pairs = 6 * s.spheres.size();
    ContactSetForm none;
    none.historySlots = 20000;
    none.persistentFlags = false;
    ContactSetForm spare = none;
    spare.lateSlots = 10000;
    const size_t table = lateTableEntriesFor(10000, 0) * sizeof(unsigned long long);
    ASSERT_EQ(table, 32768u * 8u);
    EXPECT_EQ(contactSetBytes(s, true, pairs, spare) - contactSetBytes(s, true, pairs, none),
              2 * (table - lateTableEntriesFor(0, 0) * sizeof(unsigned long long)));
    EXPECT_EQ(contactSetBytes(s, false, pairs, spare), contactSetBytes(s, false, pairs, none));
}
