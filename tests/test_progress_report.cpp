// The progress line of long DoDynamics calls and the run summary (io/ProgressReporter): the line's
// format, its rate limit, silence for short calls, at lower verbosity and when turned off, the
// terminal's redrawn line; then the same through DEMSolver, and the progress callback.
// The reporter's clock is the wall time the run monitor puts in each RunProgress, so the tests
// drive it with made-up polls.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "TestHelpers.h"
#include "io/ProgressReporter.h"

using namespace deme;
using namespace deme_test;

namespace {

RunProgress poll(double wall, double totalWall = 30.0) {
    RunProgress p;
    p.stepsTotal = 100000;
    p.stepsDone = (unsigned long long)(p.stepsTotal * wall / totalWall);
    p.simTimeEnd = 1.0;
    p.simTime = p.simTimeEnd * wall / totalWall;
    p.wallSeconds = wall;
    p.spheres = 50000;
    return p;
}

RunSummary summary() {
    RunSummary s;
    s.wallSeconds = 30, s.simSeconds = 1, s.steps = 100000, s.spheres = 50000;
    s.sphereStepsPerSecond = 50000.0 * 100000 / 30, s.contactsPerSphere = 4.5;
    s.peakHostBytes = size_t(53) << 20;
    return s;
}

// A call of `wall` seconds polled every 50 ms (the monitor's period), then its final poll.
std::string simulate(bool redraw, double wall, Verbosity v = Verbosity::INFO, bool enabled = true) {
    std::ostringstream out;
    ProgressReporter r(out, redraw);
    r.setEnabled(enabled);
    for (int k = 1; k * 0.05 < wall; k++) r.onProgress(poll(k / 20.0, wall), v, summary);
    RunProgress last = poll(wall, wall);
    last.stepsDone = last.stepsTotal;
    last.finished = true;
    r.onProgress(last, v, summary);
    return out.str();
}

std::vector<std::string> lines(const std::string& s) {
    std::vector<std::string> v;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) v.push_back(l);
    return v;
}

}  // namespace

TEST(ProgressReport, LineFormat) {
    RunProgress p = poll(10.0);  // a third of the way through a 30 s call
    EXPECT_EQ(ProgressReporter::progressLine(p),
              "[deme] t = 0.333333 of 1 s (33.3 %), 1.67e+08 sphere-steps/s, ETA 20 s");
    p = poll(100.0, 4000.0);
    EXPECT_EQ(ProgressReporter::progressLine(p),
              "[deme] t = 0.025 of 1 s (2.5 %), 1.25e+06 sphere-steps/s, ETA 1 h 05 min");
    p = poll(60.0, 200.0);
    EXPECT_EQ(ProgressReporter::progressLine(p), "[deme] t = 0.3 of 1 s (30.0 %), 2.5e+07 sphere-steps/s, ETA 2 min 20 s");
    EXPECT_EQ(ProgressReporter::summaryLine(summary(), false),
              "[deme] run: 1 s simulated in 30 s wall, 100000 steps, 1.67e+08 sphere-steps/s, 4.5 contacts/sphere, "
              "peak host memory 53.0 MiB");
    RunSummary g = summary();
    g.onGpu = true, g.deviceBytes = size_t(3) << 29, g.deviceBytesPeak = size_t(2) << 30;
    EXPECT_NE(ProgressReporter::summaryLine(g, true).find("run (stopped early): "), std::string::npos);
    EXPECT_NE(ProgressReporter::summaryLine(g, true).find(", GPU memory 1.50 GiB (at most 2.00 GiB)"), std::string::npos);
}

// Log mode: a line every 5 s of a 30 s call (at 5, 10, 15, 20, 25 s), then the summary.
TEST(ProgressReport, RateLimitedPlainLines) {
    const std::vector<std::string> l = lines(simulate(false, 30.0));
    ASSERT_EQ(l.size(), 6u);
    for (int k = 0; k < 5; k++) {
        EXPECT_EQ(l[k].rfind("[deme] t = ", 0), 0u) << l[k];
        const RunProgress expected = poll(5.0 * (k + 1));
        EXPECT_EQ(l[k], ProgressReporter::progressLine(expected));
    }
    EXPECT_EQ(l[5].rfind("[deme] run: ", 0), 0u) << l[5];
    EXPECT_EQ(simulate(false, 30.0).find('\r'), std::string::npos);
}

TEST(ProgressReport, ShortCallsLowerVerbosityAndOffAreSilent) {
    EXPECT_EQ(simulate(false, 4.9), "");
    EXPECT_EQ(simulate(true, 4.9), "");
    for (Verbosity v : {Verbosity::QUIET, Verbosity::ERROR, Verbosity::WARNING}) EXPECT_EQ(simulate(false, 30.0, v), "");
    EXPECT_EQ(simulate(false, 30.0, Verbosity::INFO, false), "");
    EXPECT_EQ(lines(simulate(false, 30.0, Verbosity::STEP_METRIC)).size(), 6u);
}

// Terminal mode: one line redrawn in place ('\r', padded over a longer previous text), ended by a
// newline and the summary when the call ends.
TEST(ProgressReport, TerminalRedrawsOneLine) {
    const std::string s = simulate(true, 30.0);
    const std::vector<std::string> l = lines(s);
    ASSERT_EQ(l.size(), 2u) << s;
    size_t redraws = 0;
    for (char c : l[0]) redraws += c == '\r';
    EXPECT_EQ(redraws, 6u);  // five reports and the final state
    EXPECT_NE(l[0].find("(100.0 %)"), std::string::npos) << l[0];
    EXPECT_EQ(l[1].rfind("[deme] run: ", 0), 0u);
}

// Through the solver: a call of a second or so with a 0.05 s interval reports at INFO and says
// nothing at WARNING; the callback sees every poll and the end.
TEST(ProgressReport, SolverReportsAndCallsBack) {
    auto run = [](const char* verbosity, int* calls, bool* sawEnd) {
        DEMSolver sim;
        sim.SetBackend("cpu");
        sim.SetVerbosity(verbosity);
        sim.SetProgressReport(true, 0.05);
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.4, 0.5));
        sim.InstructBoxDomainDimension(0.2f, 0.2f, 0.4f);
        sim.InstructBoxDomainBoundingBC("top_open", mat);
        auto pts = HCPSampler(0.0082f).SampleBox(make_float3(0, 0, -0.15f), make_float3(0.05f, 0.05f, 0.03f));
        sim.AddClumps(sim.LoadSphereType((float)sphereMass(0.004, 2600), 0.004f, mat), pts);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
        sim.SetInitTimeStep(1e-5);
        sim.Initialize();
        sim.SetProgressCallback([calls, sawEnd](const RunProgress& p) {
            ++*calls;
            *sawEnd = p.finished && p.stepsDone == p.stepsTotal;
        });
        testing::internal::CaptureStdout();
        // 5000 steps of 1512 spheres: over 0.5 s on the 2-core machines of this project, so some ten
        // polls; 1000 steps (0.15 s there) gave three polls now and then, one short of the check below.
        sim.DoDynamics(0.05);
        const RunSummary r = sim.GetRunSummary();
        EXPECT_EQ(r.steps, 5000u);
        EXPECT_NEAR(r.simSeconds, 0.05, 1e-12);
        EXPECT_GT(r.sphereStepsPerSecond, 0.0);
        EXPECT_GT(r.peakHostBytes, 0u);
        return testing::internal::GetCapturedStdout();
    };
    int calls = 0;
    bool sawEnd = false;
    const std::string info = run("INFO", &calls, &sawEnd);
    EXPECT_NE(info.find("[deme] t = "), std::string::npos) << info;
    EXPECT_NE(info.find("[deme] run: 0.05 s simulated"), std::string::npos) << info;
    EXPECT_GT(calls, 3);
    EXPECT_TRUE(sawEnd);
    const std::string quiet = run("WARNING", &calls, &sawEnd);
    EXPECT_EQ(quiet.find("[deme]"), std::string::npos) << quiet;
}

// An exception from the callback stops the call at a step boundary and comes out of DoDynamics.
TEST(ProgressReport, CallbackExceptionStopsTheCall) {
    DEMSolver sim;
    sim.SetVerbosity("QUIET");
    auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.4, 0.5));
    sim.InstructBoxDomainDimension(1, 1, 1);
    sim.AddClumps(sim.LoadSphereType(1.f, 0.01f, mat), {make_float3(0, 0, 0)});
    sim.SetInitTimeStep(1e-5);
    sim.Initialize();
    sim.SetProgressCallback([](const RunProgress& p) {
        if (p.stepsDone > 0 && !p.finished) throw std::runtime_error("stop here");
    });
    EXPECT_THROW(sim.DoDynamics(1000.0), std::runtime_error);
    const double steps = sim.GetSimTime() / 1e-5;
    EXPECT_GT(steps, 0.0);
    EXPECT_LT(sim.GetSimTime(), 1000.0);
    EXPECT_NEAR(steps, std::round(steps), 1e-6);
    sim.SetProgressCallback(nullptr);
    sim.DoDynamics(1e-4);  // goes on from there
}
