// Watches one DoDynamics call from between its steps, where the state is consistent: progress
// reports and interrupt requests (a GUI's stop button, Ctrl-C in Python) are hooks it polls about
// every POLL_SECONDS of wall time, so that they cost nothing on a step's scale. A hook that returns
// true stops the call after the current step; the run can go on with the next call. The steps run
// in batches (runtime/Simulation.cpp); the monitor sizes them from the measured time per step, so
// that a batch ends about when the next poll is due, and a slow step (a large scene on the CPU)
// makes a batch of one.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>

#include <deme/RunProgress.h>

namespace deme {

// Returns true to stop the call after the step just taken.
using RunHook = std::function<bool(const RunProgress&)>;

class RunMonitor {
  public:
    static constexpr double POLL_SECONDS = 0.05;

    // Hooks are kept by id until removed; polled in id order.
    int addHook(RunHook hook) {
        m_hooks[m_nextId] = std::move(hook);
        return m_nextId++;
    }
    void removeHook(int id) { m_hooks.erase(id); }
    bool empty() const { return m_hooks.empty(); }

    void begin(unsigned long long steps, double simTime, double dt, size_t spheres) {
        m_progress = RunProgress{};
        m_progress.stepsTotal = steps;
        m_progress.simTime = simTime;
        m_progress.simTimeEnd = simTime + (double)steps * dt;
        m_progress.spheres = spheres;
        m_start = m_lastPoll = m_batchStart = std::chrono::steady_clock::now();
        m_stopped = m_pollPending = false;
    }
    // Before a batch of steps: how many may run before the hooks are next due (no limit without
    // hooks; one step while the time per step is not yet known).
    unsigned long long stepsBeforePoll() {
        m_batchStart = std::chrono::steady_clock::now();
        if (m_hooks.empty()) return ~0ull;
        const double left = POLL_SECONDS - seconds(m_batchStart - m_lastPoll);
        if (!(m_secondsPerStep > 0.0) || left <= m_secondsPerStep) return 1;
        return (unsigned long long)std::min(left / m_secondsPerStep, 1e9);
    }
    // Before a batch of `steps` steps: whether the hooks are polled after its last one (when the
    // poll falls due by then). The GPU stores per-contact forces in such a step, so that a call
    // stopped after it leaves them current.
    bool pollsAfter(unsigned long long steps) {
        m_pollPending = !m_hooks.empty() &&
                        seconds(m_batchStart - m_lastPoll) + (double)steps * m_secondsPerStep >= POLL_SECONDS;
        return m_pollPending;
    }
    // After a batch: `steps` were taken, and `asPlanned` says whether the batch ran to the end that
    // pollsAfter was asked about. True: stop the call now.
    bool afterSteps(unsigned long long steps, bool asPlanned, double simTime) {
        const auto now = std::chrono::steady_clock::now();
        m_progress.stepsDone += steps;
        if (steps > 0) m_secondsPerStep = seconds(now - m_batchStart) / (double)steps;
        if (!m_pollPending) return false;
        m_pollPending = false;
        if (!asPlanned) return false;  // polled after the batch that reaches that step
        m_lastPoll = now;
        m_progress.simTime = simTime;
        m_progress.wallSeconds = seconds(m_lastPoll - m_start);
        m_stopped = poll();
        return m_stopped;
    }
    // After the call's last step (or the one it stopped at).
    void end(double simTime) {
        m_progress.simTime = simTime;
        m_progress.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
        m_progress.finished = true;
        if (!m_hooks.empty()) poll();
    }
    // Whether the last call was stopped by a hook before its last step.
    bool stopped() const { return m_stopped; }
    const RunProgress& progress() const { return m_progress; }

  private:
    static double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }
    bool poll() {
        bool stop = false;
        for (auto& h : m_hooks) stop = h.second(m_progress) || stop;
        return stop;
    }
    std::map<int, RunHook> m_hooks;
    int m_nextId = 0;
    RunProgress m_progress;
    std::chrono::steady_clock::time_point m_start, m_lastPoll, m_batchStart;
    double m_secondsPerStep = 0.0;  // of the last batch (kept between calls: the same scene, most likely)
    bool m_stopped = false, m_pollPending = false;
};

}  // namespace deme
