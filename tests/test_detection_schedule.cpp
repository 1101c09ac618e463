// The dynamics side's contact-set schedule (runtime/DetectionSchedule.h), shared by the CPU's
// kinematics thread and the GPU's kinematics stream: checked here without either, against a model
// kinematics side that delivers each order a fixed number of steps after it was sent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "runtime/DetectionSchedule.h"

using namespace deme;

namespace {

Settings settingsWith(unsigned int n, bool adaptive) {
    Settings s;
    s.dt = 1e-5;
    s.gravity = make_float3(0.f, 0.f, -9.81f);
    s.updateFreq = n;
    s.maxUpdateFreq = 200;
    s.adaptiveUpdateFreq = adaptive;
    return s;
}

// The dynamics loop of ContactSetManager::prepareStep / DeviceSimulation's prepareStep with a model
// kinematics side of fixed latency, and owners that travel `travelPerStep` each step.
struct LoopModel {
    DetectionSchedule sched;
    CollaborationStats stats;
    Settings settings;
    unsigned int latency = 3;
    double travelPerStep = 0.0;
    // The order in flight.
    bool inFlight = false;
    unsigned long long orderStep = 0, orderGeneration = 0, readyAt = 0;
    double orderMargin = 0.0, orderTravel = 0.0;
    // State.
    double travel = 0.0, setTravel = 0.0;
    unsigned long long inlineDetections = 0, stepsOnExpiredSet = 0;
    // Costs, for a kinematics side on the dynamics' device: a detection's time, the force pass per
    // step, and false positives growing with the margin, i.e. with n_max.
    double detectSeconds = 0.0, forcePerStep = 0.0, forceSeconds = 0.0, falsePositivesPer20 = 0.0;

    void detectNow(unsigned long long step) {
        sched.beforeSyncDetection(settings.asyncDetection, step, stats, 0.0);
        sched.installed(step, sched.marginFor(settings, 0.f), stats);
        setTravel = travel;
        sched.afterSyncDetection(stats, 0.0, 0.0);
        inlineDetections++;
    }
    void take(unsigned long long step) {
        inFlight = false;
        if (sched.accept(orderStep, orderGeneration, orderMargin, step, stats,
                         [&] { return travel - orderTravel; })) {
            sched.installed(orderStep, orderMargin, stats);
            sched.afterAsyncResult(stats, forceSeconds, detectSeconds);
            setTravel = orderTravel;
        }
    }
    // Steps between looks at the schedule (runtime/Simulation's batches): 0 looks before every step;
    // otherwise the loop runs batches of stepsBeforeReview(step, async, batchPoll) steps, each ended
    // early after a step that lets the set in use expire (dynamics/StepBatch.h).
    unsigned int batchPoll = 0;
    unsigned long long batches = 0, latestTake = 0;

    void decide(unsigned long long step) {
        if (sched.needsDetection()) detectNow(step);
        if (inFlight && step >= readyAt) {
            latestTake = std::max(latestTake, step - readyAt);
            take(step);
        }
        if (sched.due(step)) {
            stats.dynamicsWaits++;
            if (inFlight) take(step);  // waits for it
            if (sched.due(step)) detectNow(step);
        }
        if (sched.shouldOrder(step)) {
            inFlight = true;
            orderStep = step;
            orderGeneration = sched.generation();
            orderMargin = sched.marginFor(settings, 0.f);
            orderTravel = travel;
            readyAt = step + latency;
            sched.ordered(stats);
        }
    }
    // The step itself: it must run on a set that is still valid. True: it ends its batch.
    bool step(unsigned long long step) {
        if (travel - setTravel > sched.margin() || step - sched.acsStep() > sched.nMax()) stepsOnExpiredSet++;
        travel += travelPerStep;
        forceSeconds += forcePerStep;
        stats.contactSetSizeSum += 1.0;
        stats.realContactSum += 1.0 - std::min(1.0, falsePositivesPer20 * sched.nMax() / 20.0);
        stats.steps++;
        sched.afterStep(travel - setTravel);
        return travel - setTravel > sched.margin();
    }
    void run(unsigned long long from, unsigned long long to) {
        for (unsigned long long s = from; s < to;) {
            decide(s);
            const unsigned long long k =
                batchPoll ? std::min(to - s, sched.stepsBeforeReview(s, settings.asyncDetection, batchPoll)) : 1;
            batches++;
            for (unsigned long long j = 0; j < k; j++)
                if (step(s++)) break;
        }
    }
};

}  // namespace

TEST(DetectionSchedule, MarginCoversTheSpeedBoundOverNmaxSteps) {
    DetectionSchedule s;
    Settings set = settingsWith(20, false);
    set.maxVelocity = 2.f;
    set.safetyMultiplier = 1.1f;
    set.safetyAdder = 1e-4f;
    s.configure(set);
    // (2 m/s + 9.81 x 20 dt) x 20 dt x 1.1 + adder; a measured speed above the bound takes over.
    const double vBound = 2.0 + std::sqrt(9.81 * 9.81) * 20 * 1e-5;
    EXPECT_NEAR(s.marginFor(set, 0.f), 1.1 * vBound * 20 * 1e-5 + 1e-4, 1e-9);
    EXPECT_NEAR(s.marginFor(set, 5.f), 1.1 * (5.0 + 9.81 * 20 * 1e-5) * 20 * 1e-5 + 1e-4, 1e-9);
}

TEST(DetectionSchedule, SetExpiresAfterNmaxStepsOrBeyondItsMargin) {
    DetectionSchedule s;
    s.configure(settingsWith(10, false));
    CollaborationStats stats;
    EXPECT_TRUE(s.due(0));  // nothing detected yet
    s.installed(0, 1e-3, stats);
    EXPECT_EQ(stats.acsUpdates, 1u);
    EXPECT_FALSE(s.due(9));
    EXPECT_TRUE(s.due(10));
    s.afterStep(0.9e-3);
    EXPECT_FALSE(s.due(5));
    s.afterStep(1.1e-3);  // an owner travelled beyond the margin
    EXPECT_TRUE(s.due(5));
    s.installed(5, 1e-3, stats);
    EXPECT_FALSE(s.due(5));
    s.invalidate();  // a host edit
    EXPECT_TRUE(s.due(5));
    EXPECT_TRUE(s.needsDetection());
}

// A sheared cell limits a set's age below n_max (limitAge): the set expires then, the margin covers
// that many steps, and a batch stops there; 0 lifts the limit.
TEST(DetectionSchedule, ShearedCellLimitsTheSetsAge) {
    DetectionSchedule s;
    const Settings settings = settingsWith(10, false);
    s.configure(settings);
    CollaborationStats stats;
    const double margin10 = s.marginFor(settings, 1.f);
    s.limitAge(4);
    EXPECT_EQ(s.nMax(), 4u);
    const double vBound = 1.0 + (double)length(settings.gravity) * 4 * settings.dt;
    EXPECT_NEAR(s.marginFor(settings, 1.f), settings.safetyMultiplier * vBound * settings.dt * 4 + settings.safetyAdder,
                1e-12);
    EXPECT_LT(s.marginFor(settings, 1.f), margin10);
    s.installed(0, 1e-3, stats);
    EXPECT_FALSE(s.due(3));
    EXPECT_TRUE(s.due(4));
    EXPECT_EQ(s.stepsBeforeReview(1, false, 16), 3u);
    s.limitAge(0);
    EXPECT_EQ(s.nMax(), 10u);
    EXPECT_FALSE(s.due(4));
}

TEST(DetectionSchedule, ResultsAreRejectedWhenStaleOrTravelledTooFar) {
    DetectionSchedule s;
    s.configure(settingsWith(10, true));
    CollaborationStats stats;
    s.installed(0, 1e-3, stats);
    s.ordered(stats);
    EXPECT_TRUE(s.orderInFlight());
    EXPECT_FALSE(s.shouldOrder(100));  // one order at a time
    bool asked = false;
    EXPECT_TRUE(s.accept(2, s.generation(), 1e-3, 5, stats, [&] {
        asked = true;
        return 0.5e-3;
    }));
    EXPECT_TRUE(asked);
    EXPECT_FALSE(s.orderInFlight());
    EXPECT_EQ(stats.latencyStepsSum, 3.0);
    // Travelled beyond the order's margin since its snapshot.
    s.ordered(stats);
    EXPECT_FALSE(s.accept(5, s.generation(), 1e-3, 8, stats, [] { return 2e-3; }));
    EXPECT_EQ(stats.discardedResults, 1u);
    // Ordered before a host edit: stale, and the travel is not even looked at.
    s.ordered(stats);
    const unsigned long long before = s.generation();
    s.invalidate();
    asked = false;
    EXPECT_FALSE(s.accept(8, before, 1e-3, 9, stats, [&] {
        asked = true;
        return 0.0;
    }));
    EXPECT_FALSE(asked);
    EXPECT_EQ(stats.discardedResults, 2u);
    EXPECT_EQ(stats.ordersSent, 3u);
}

// With a kinematics side of latency L, every step runs on a valid set, the dynamics side waits only
// while n_max adapts (towards 2.25 L + 2) and then no more, and every set after the first arrives
// from an order, none from a detection the dynamics side ran in line.
TEST(DetectionSchedule, AsyncLoopNeverStepsOnAnExpiredSetAndStopsWaiting) {
    LoopModel m;
    m.settings = settingsWith(2, true);
    m.settings.asyncDetection = true;
    m.settings.maxVelocity = 1.f;
    m.sched.configure(m.settings);
    m.latency = 6;
    m.travelPerStep = 1e-6;  // well inside the margin: sets run out by age only
    m.run(0, 1000);
    const unsigned long long earlyWaits = m.stats.dynamicsWaits;
    EXPECT_GT(earlyWaits, 0u);  // n_max 2 is shorter than the latency at first
    m.run(1000, 3000);
    EXPECT_EQ(m.stats.dynamicsWaits, earlyWaits);
    EXPECT_EQ(m.stepsOnExpiredSet, 0u);
    EXPECT_GE(m.sched.nMax(), 6u + 2u);
    EXPECT_LE(m.sched.nMax(), (unsigned int)std::ceil(2.25 * 6) + 2);
    EXPECT_EQ(m.inlineDetections, 1u);  // the first set only
    EXPECT_GT(m.stats.acsUpdates, 3000u / m.sched.nMax());
    EXPECT_EQ(m.stats.discardedResults, 0u);
}

// Fast owners: sets expire by travel before n_max; a result whose snapshot is too far behind is
// dropped, and the loop still never steps on an expired set.
TEST(DetectionSchedule, AsyncLoopWithFastOwnersStaysSafe) {
    LoopModel m;
    m.settings = settingsWith(20, true);
    m.settings.asyncDetection = true;
    m.settings.maxVelocity = 0.01f;  // the bound is far too small: the sets expire by travel
    m.sched.configure(m.settings);
    m.latency = 4;
    m.travelPerStep = 5e-7;  // the margin (about 2.6e-6) is used up in 6 steps
    m.run(0, 3000);
    EXPECT_EQ(m.stepsOnExpiredSet, 0u);
    EXPECT_GT(m.stats.dynamicsWaits, 0u);
}

// kT on dT's GPU: n_max settles where D/n^2 = F/2 c, the minimum of D/n + F/2 phi(n) with
// phi(n) = c n, i.e. sqrt(2 D / (F c)) = sqrt(2 x 0.02 / (0.004 x 0.05 / 20)) = 63 steps, well above
// the latency bound (2.25 x 5 + 2), with every step still on a valid set and no more waiting once it
// has adapted.
TEST(DetectionSchedule, AsyncLoopOnTheDynamicsDeviceBalancesDetectionCost) {
    LoopModel m;
    m.settings = settingsWith(20, true);
    m.settings.asyncDetection = true;
    m.settings.maxVelocity = 1.f;
    m.sched.configure(m.settings, true);
    m.latency = 5;
    m.travelPerStep = 1e-7;
    m.detectSeconds = 0.02;
    m.forcePerStep = 0.004;
    m.falsePositivesPer20 = 0.05;
    m.run(0, 4000);
    const unsigned long long waits = m.stats.dynamicsWaits, updates = m.stats.acsUpdates;
    m.run(4000, 8000);
    EXPECT_EQ(m.stepsOnExpiredSet, 0u);
    EXPECT_EQ(m.stats.dynamicsWaits, waits);
    EXPECT_NEAR((double)m.sched.nMax(), 63.0, 3.0);
    // About every 63 - (1.25 x 5 + 1) = 55 steps. The same loop with kT on its own device keeps
    // the floor and detects about every 20 - 8 = 12 steps.
    EXPECT_NEAR((double)(m.stats.acsUpdates - updates), 4000.0 / 55.0, 8.0);
    LoopModel own = m;
    own.sched = DetectionSchedule();
    own.sched.configure(own.settings, false);
    own.stats = CollaborationStats();
    own.run(0, 4000);
    EXPECT_EQ(own.sched.nMax(), 20u);
    EXPECT_GT(own.stats.acsUpdates, 4 * (m.stats.acsUpdates - updates));
}

// Synchronous mode: detections only, every n_max steps; n_max follows the cost balance.
TEST(DetectionSchedule, SyncLoopDetectsEveryNmaxSteps) {
    LoopModel m;
    m.settings = settingsWith(10, false);
    m.settings.asyncDetection = false;
    m.sched.configure(m.settings);
    for (unsigned long long step = 0; step < 100; step++) {
        if (m.sched.due(step)) m.detectNow(step);
        m.stats.steps++;
        m.sched.afterStep(0.0);
    }
    EXPECT_EQ(m.inlineDetections, 10u);
    EXPECT_EQ(m.stats.syncDetections, 10u);
    EXPECT_EQ(m.stats.ordersSent, 0u);
}

// Batches (runtime/Simulation: the host looks only between them): every step still runs on a valid
// set, in both modes, with sets expiring by age and by travel; asynchronously, a result is taken at
// most one poll interval after it is ready, the waits stop once n_max has adapted, and the host looks
// far less often than every step.
TEST(DetectionSchedule, BatchedLoopNeverStepsOnAnExpiredSet) {
    for (bool async : {true, false})
        for (double travelPerStep : {1e-7, 5e-7}) {
            SCOPED_TRACE(std::string(async ? "async" : "sync") + ", travel per step " + std::to_string(travelPerStep));
            LoopModel m;
            m.settings = settingsWith(async ? 2 : 40, true);
            m.settings.asyncDetection = async;
            m.settings.maxVelocity = travelPerStep > 2e-7 ? 0.01f : 1.f;  // the fast case expires by travel
            m.sched.configure(m.settings);
            m.latency = 6;
            m.travelPerStep = travelPerStep;
            m.batchPoll = 16;
            m.run(0, 2000);
            const unsigned long long waits = m.stats.dynamicsWaits;
            m.run(2000, 6000);
            EXPECT_EQ(m.stepsOnExpiredSet, 0u);
            EXPECT_EQ(m.stats.steps, 6000u);
            if (async) EXPECT_LT(m.latestTake, 16u);
            if (travelPerStep < 2e-7) {
                EXPECT_LT(m.batches, 6000u / 4);
                if (async) EXPECT_EQ(m.stats.dynamicsWaits, waits);
            }
        }
}

// The review horizon: up to the set's n_max, up to the order's step with none in flight, and the
// poll interval with one in flight; never zero.
TEST(DetectionSchedule, StepsBeforeReview) {
    DetectionSchedule s;
    s.configure(settingsWith(40, false));
    CollaborationStats stats;
    s.installed(100, 1e-3, stats);
    EXPECT_EQ(s.stepsBeforeReview(100, false, 16), 40u);
    EXPECT_EQ(s.stepsBeforeReview(130, false, 16), 10u);
    EXPECT_EQ(s.stepsBeforeReview(140, false, 16), 1u);  // due: detected at the next look
    // Asynchronous, no latency observed yet: an order is due at once, then looks every 16 steps.
    EXPECT_EQ(s.stepsBeforeReview(100, true, 16), 40u);
    s.ordered(stats);
    EXPECT_EQ(s.stepsBeforeReview(100, true, 16), 16u);
    EXPECT_EQ(s.stepsBeforeReview(135, true, 16), 5u);
}
