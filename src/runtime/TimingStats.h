// Wall time spent per phase of the step loop, for ShowTimingStats().
#pragma once

#include <chrono>
#include <string>

namespace deme {

enum class Phase { BINNING = 0, PAIR_SEARCH, HISTORY_MAPPING, FORCE, REDUCTION, INTEGRATION, EXCHANGE, COUNT };

struct TimingStats {
    // Binning and pair search run on the kinematics thread when detection is asynchronous; the
    // other phases on the dynamics thread.
    double seconds[(int)Phase::COUNT] = {};
    unsigned long long steps = 0;
    static const char* name(Phase p) {
        static const char* names[] = {"binning (kinematics)",
                                      "pair search (kinematics)",
                                      "history mapping",
                                      "force calculation",
                                      "force reduction",
                                      "integration",
                                      "exchange"};
        return names[(int)p];
    }
};

// Adds the lifetime of this object to one phase.
class PhaseTimer {
  public:
    PhaseTimer(TimingStats& stats, Phase p) : m_stats(stats), m_phase(p), m_start(std::chrono::steady_clock::now()) {}
    ~PhaseTimer() {
        m_stats.seconds[(int)m_phase] +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    }

  private:
    TimingStats& m_stats;
    Phase m_phase;
    std::chrono::steady_clock::time_point m_start;
};

}  // namespace deme
