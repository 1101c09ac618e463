// Watches one DoDynamics call from between its steps, where the state is consistent: progress
// reports and interrupt requests (a GUI's stop button, Ctrl-C in Python) are hooks it polls at most
// every `pollSeconds` of wall time, so that they cost nothing on a step's scale. A hook that returns
// true stops the call after the current step; the run can go on with the next call.
#pragma once

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
        m_start = m_lastPoll = std::chrono::steady_clock::now();
        m_stopped = m_pollPending = false;
    }
    // Before each step: whether the hooks are polled after it (the clock is read every 8 steps
    // only). The GPU stores per-contact forces in such a step, so that a call stopped after it
    // leaves them current.
    bool pollsAfterThisStep() {
        m_pollPending = false;
        if (m_hooks.empty() || ((m_progress.stepsDone + 1) & 7) != 0) return false;
        const auto now = std::chrono::steady_clock::now();
        m_pollPending = std::chrono::duration<double>(now - m_lastPoll).count() >= POLL_SECONDS;
        return m_pollPending;
    }
    // After each step; true: stop the call now.
    bool afterStep(double simTime) {
        m_progress.stepsDone++;
        if (!m_pollPending) return false;
        m_pollPending = false;
        m_lastPoll = std::chrono::steady_clock::now();
        m_progress.simTime = simTime;
        m_progress.wallSeconds = std::chrono::duration<double>(m_lastPoll - m_start).count();
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
    bool poll() {
        bool stop = false;
        for (auto& h : m_hooks) stop = h.second(m_progress) || stop;
        return stop;
    }
    std::map<int, RunHook> m_hooks;
    int m_nextId = 0;
    RunProgress m_progress;
    std::chrono::steady_clock::time_point m_start, m_lastPoll;
    bool m_stopped = false, m_pollPending = false;
};

}  // namespace deme
