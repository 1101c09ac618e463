// Adapts n_max, the number of steps the dynamics side may advance on one active-contact set, from
// the measured latency of the kinematics side (paper §2.1): small enough to keep the margin and the
// false positives small, large enough that dynamics rarely waits.
#pragma once

#include <algorithm>
#include <cmath>

namespace deme {

class UpdateFrequency {
  public:
    void configure(unsigned int initial, unsigned int maximum, bool adaptive) {
        m_max = std::max(1u, maximum);
        m_n = std::min(std::max(1u, initial), m_max);
        m_adaptive = adaptive;
        m_latency = -1.0;
    }
    unsigned int nMax() const { return m_n; }
    bool adaptive() const { return m_adaptive; }

    // One detection was ordered `latencySteps` steps before its result reached the dynamics side.
    // With a new order sent as soon as the previous result arrives, a contact set is used from about
    // one latency after its snapshot until the next one arrives, about two latencies after it: n_max
    // covers that with 25 % headroom (and at least 2 steps). The latency is smoothed, so that one
    // slow detection does not swing the margin.
    void observeLatency(unsigned int latencySteps) {
        const double l = (double)latencySteps;
        m_latency = m_latency < 0.0 ? l : 0.8 * m_latency + 0.2 * l;
        if (!m_adaptive) return;
        const double target = std::ceil(2.5 * m_latency) + 2.0;
        m_n = (unsigned int)std::min<double>(std::max(target, 1.0), (double)m_max);
    }
    double smoothedLatency() const { return m_latency; }

  private:
    unsigned int m_n = 20, m_max = 1000;
    bool m_adaptive = true;
    double m_latency = -1.0;
};

}  // namespace deme
