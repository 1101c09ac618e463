#include "runtime/StatsReport.h"

#include <iomanip>
#include <sstream>

#include "runtime/Simulation.h"

namespace deme {

std::string timingReport(const Simulation& sim) {
    const TimingStats& t = sim.timing();
    double total = 0.0;
    for (double s : t.seconds) total += s;
    std::ostringstream os;
    os << std::fixed << std::setprecision(3);
    os << "Timing over " << t.steps << " steps (seconds of thread time per phase):\n";
    for (int p = 0; p < (int)Phase::COUNT; p++)
        os << "  " << std::setw(26) << std::left << TimingStats::name((Phase)p) << std::right << std::setw(10)
           << t.seconds[p] << " s  " << std::setw(6) << std::setprecision(1)
           << (total > 0 ? 100.0 * t.seconds[p] / total : 0.0) << " %" << std::setprecision(3) << "\n";
    const double wall = sim.contactSets().stats().dynamicsSeconds;
    os << "  step loop wall time " << wall << " s";
    if (wall > 0 && t.steps > 0)
        os << ", " << std::scientific << std::setprecision(3)
           << (double)sim.numSpheres() * (double)t.steps / wall << " sphere-steps/s";
    const std::string launches = sim.launchReport();
    if (!launches.empty()) os << "\n  " << launches;
    return os.str();
}

std::string collaborationReport(const Simulation& sim) {
    const ContactSetManager& m = sim.contactSets();
    const CollaborationStats& c = m.stats();
    std::ostringstream os;
    os << std::fixed << std::setprecision(3);
    const double steps = (double)std::max<unsigned long long>(c.steps, 1);
    const double received = (double)(c.ordersSent > 0 ? c.ordersSent : 1);
    os << "Kinematics/dynamics collaboration over " << c.steps << " steps ("
       << (sim.settings.onGpu ? (sim.settings.asyncDetection ? "on the GPU, asynchronous" : "on the GPU, synchronous")
           : sim.settings.asyncDetection ? "asynchronous"
                                         : "synchronous")
       << " detection):\n"
       << "  contact-set updates " << c.acsUpdates << " (" << c.syncDetections << " detected on the dynamics thread, "
       << c.ordersSent << " ordered from the kinematics thread, " << c.discardedResults << " discarded as stale)\n"
       << "  average steps per update " << (c.acsUpdates ? steps / (double)c.acsUpdates : 0.0) << ", n_max now "
       << sim.updateFreq() << (m.frequency().adaptive() ? " (adaptive)" : " (fixed)") << ", margin "
       << std::scientific << sim.currentMargin() << std::fixed << " m\n"
       << "  dynamics waited " << c.dynamicsWaits << " times, " << c.dynamicsWaitSeconds
       << " s = " << std::setprecision(2)
       << (c.dynamicsSeconds > 0 ? 100.0 * c.dynamicsWaitSeconds / c.dynamicsSeconds : 0.0) << " % of the step loop\n"
       << "  kinematics latency " << std::setprecision(1) << c.latencyStepsSum / received << " steps on average\n"
       << "  contact set: " << std::setprecision(0) << c.contactSetSizeSum / steps << " pairs on average, "
       << std::setprecision(1)
       << (c.contactSetSizeSum > 0 ? 100.0 * (1.0 - c.realContactSum / c.contactSetSizeSum) : 0.0)
       << " % false positives (pairs not in contact)\n"
       << "  step batches " << c.batches << " (the host looked between steps every " << std::setprecision(1)
       << (c.batches ? steps / (double)c.batches : 0.0) << " steps on average), " << c.batchesEndedEarly
       << " ended early by an expired contact set or a fault";
    return os.str();
}

std::string memoryReport(const MemoryStats& m) {
    std::ostringstream os;
    const double perSphere = m.spheres ? 1.0 / (double)m.spheres : 0.0;
    auto mib = [](size_t b) { return (double)b / (1 << 20); };
    // A GPU run also shows each group at the device's peak (where the peak comes from).
    const bool peak = m.devicePeakTotal() > 0;
    os << "Memory by array group (" << m.spheres << " spheres; MiB, and bytes per sphere):\n";
    os << "  " << std::left << std::setw(22) << "group" << std::right << std::setw(12) << "device MiB" << std::setw(10)
       << "B/sphere" << std::setw(12) << "host MiB" << std::setw(10) << "B/sphere";
    if (peak) os << std::setw(14) << "device peak" << std::setw(10) << "B/sphere";
    os << "\n" << std::fixed;
    auto column = [&](size_t b) {
        os << std::setprecision(1) << std::setw(12) << mib(b) << std::setprecision(0) << std::setw(10)
           << (double)b * perSphere;
    };
    for (int g = 0; g <= NUM_MEMORY_GROUPS; g++) {
        const bool total = g == NUM_MEMORY_GROUPS;
        os << "  " << std::left << std::setw(22) << (total ? "total" : memoryGroupName((MemoryGroup)g)) << std::right;
        column(total ? m.deviceTotal() : m.deviceBytes[g]);
        column(total ? m.hostTotal() : m.hostBytes[g]);
        if (peak) {
            os << "  ";
            column(total ? m.devicePeakTotal() : m.devicePeakBytes[g]);
        }
        if (!total) os << "\n";
    }
    return os.str();
}

}  // namespace deme
