// Wall time spent per phase of the step loop, for ShowTimingStats().
#pragma once

#include <chrono>
#include <string>

namespace deme {

enum class Phase { DETECTION = 0, HISTORY_MAPPING, FORCE, INTEGRATION, COUNT };

struct TimingStats {
    double seconds[(int)Phase::COUNT] = {0.0, 0.0, 0.0, 0.0};
    unsigned long long steps = 0, detections = 0, earlyDetections = 0;
    double contactsPerDetection = 0.0;  // running sum, divided by detections when shown
    static const char* name(Phase p) {
        static const char* names[] = {"contact detection", "history mapping", "force calculation",
                                      "reduction + integration"};
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
