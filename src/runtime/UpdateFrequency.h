// Adapts n_max, the number of steps the dynamics side may advance on one active-contact set, from
// the measured latency of the kinematics side (paper §2.1): small enough to keep the margin and the
// false positives small, large enough that dynamics rarely waits.
#pragma once

#include <algorithm>
#include <cmath>

namespace deme {

class UpdateFrequency {
  public:
    // detectionSharesDynamics: the kinematics side runs on the dynamics side's device (one GPU, two
    // streams), so its kernels take the dynamics' multiprocessors and memory bandwidth: asynchronous
    // detection is not free there, and n_max also balances its cost (observeSharedCost).
    void configure(unsigned int initial, unsigned int maximum, bool adaptive, bool detectionSharesDynamics = false) {
        m_max = std::max(1u, maximum);
        m_floor = m_n = m_costN = std::min(std::max(1u, initial), m_max);
        m_latencyN = 0;
        m_adaptive = adaptive;
        m_shared = detectionSharesDynamics;
        m_latency = -1.0;
    }
    bool detectionSharesDynamics() const { return m_shared; }
    unsigned int nMax() const { return m_n; }
    bool adaptive() const { return m_adaptive; }

    // One detection was ordered `latencySteps` steps before its result reached the dynamics side.
    // A set arrives about one latency L after its snapshot, and its successor cannot be ordered
    // before that, so it arrives about 2L after the set's snapshot at the earliest: n_max needs 2L
    // plus headroom. Orders go out just in time (orderAge()) when n_max is larger than that. On the CPU the
    // kinematics thread shares the cores with the dynamics team, so detecting more often than the
    // user's n_max would only slow the dynamics down: that value stays the floor, and n_max rises
    // above it only when kinematics cannot keep up. The latency is smoothed, so one slow detection
    // does not swing the margin. Where detection shares the dynamics' device, the cost balance
    // (observeSharedCost) takes the floor's place.
    void observeLatency(unsigned int latencySteps) {
        const double l = (double)latencySteps;
        m_latency = m_latency < 0.0 ? l : 0.8 * m_latency + 0.2 * l;
        if (!m_adaptive) return;
        m_latencyN = (unsigned int)std::min<double>(std::ceil(2.25 * m_latency - 1e-6) + 2.0, (double)m_max);
        combine();
    }
    // Synchronous detection: one detection cost `detectSeconds`; since the previous one, a step's
    // force pass took `forceSecondsPerStep` on average with a share `falsePositives` of the set not
    // in contact. Detection costs D/n per step; false positives grow with the margin, i.e. with n,
    // and cost about half a real contact each: per step ~ F/2 * phi(n) with phi(n) = phi * n / n_now.
    // The n minimising the sum is sqrt(D n_now / (F/2 phi)); n_max moves towards it by at most a
    // factor 2 per detection.
    void observeSyncCost(double detectSeconds, double forceSecondsPerStep, double falsePositives) {
        if (!m_adaptive || !(forceSecondsPerStep > 0.0) || !(detectSeconds > 0.0)) return;
        m_n = m_costN = costBalance(detectSeconds, forceSecondsPerStep, falsePositives);
    }
    // Asynchronous detection on the dynamics' device: the same balance, with the kinematics side's
    // time for one detection as its cost (an upper bound of what it took from the dynamics, since
    // the two streams overlap), but n_max never below what the latency needs (observeLatency).
    // Measured on one H200 (BENCHMARKS.md): without it, a detection of a few steps' latency was
    // ordered every dozen steps and the step rate fell below the synchronous mode's.
    void observeSharedCost(double detectSeconds, double forceSecondsPerStep, double falsePositives) {
        if (!m_adaptive || !m_shared || !(forceSecondsPerStep > 0.0) || !(detectSeconds > 0.0)) return;
        m_costN = costBalance(detectSeconds, forceSecondsPerStep, falsePositives);
        combine();
    }

    // Age (steps since its snapshot) at which the current set's successor should be ordered.
    unsigned int orderAge() const {
        if (m_latency < 0.0) return 0;
        const double lead = std::ceil(1.25 * m_latency - 1e-6) + 1.0;
        return (unsigned int)std::max(0.0, (double)m_n - lead);
    }
    double smoothedLatency() const { return m_latency; }

    // What the controller has learned during a run (not what configure() sets), for a checkpoint:
    // a restarted run goes on with the n_max it had adapted to instead of starting over.
    struct Learned {
        unsigned int n = 0, costN = 0, latencyN = 0;
        double latency = -1.0;
    };
    Learned learned() const { return Learned{m_n, m_costN, m_latencyN, m_latency}; }
    // Within this run's configuration: never above its cap, and in synchronous/fixed use never
    // below its floor (a different SetCDMaxUpdateFreq in the restarted script wins).
    void restore(const Learned& l) {
        m_latency = l.latency;
        m_latencyN = std::min(l.latencyN, m_max);
        m_costN = std::min(std::max(1u, l.costN), m_max);
        m_n = m_adaptive ? std::min(std::max(1u, l.n), m_max) : m_n;
    }

  private:
    // The n minimising D/n + F/2 phi n / n_now, moved by at most a factor 2 from n_now = m_n.
    unsigned int costBalance(double detectSeconds, double forceSecondsPerStep, double falsePositives) const {
        const double phi = std::max(falsePositives, 1e-3);
        const double n = (double)m_n;
        double target = std::sqrt(detectSeconds * n / (0.5 * forceSecondsPerStep * phi));
        target = std::min(std::max(target, 0.5 * n), 2.0 * n);
        return (unsigned int)std::min(std::max(std::round(target), 1.0), (double)m_max);
    }
    // Asynchronous mode: what the latency needs, and no less than the floor or, where detection
    // shares the dynamics' device, the cost balance.
    void combine() { m_n = std::min(std::max(m_latencyN, m_shared ? m_costN : m_floor), m_max); }

    unsigned int m_n = 20, m_max = 1000, m_floor = 1, m_costN = 20, m_latencyN = 0;
    bool m_adaptive = true, m_shared = false;
    double m_latency = -1.0;
};

}  // namespace deme
