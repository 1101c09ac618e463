#include "io/ProgressReporter.h"

#include <cmath>
#include <cstdio>

#include <sys/resource.h>

namespace deme {

namespace {

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
    char buf[128];
    std::snprintf(buf, sizeof buf, fmt, a, b, c);
    return buf;
}

std::string duration(double s) {
    const long t = std::lround(s);
    if (t >= 3600) return format("%.0f h %02.0f min", (double)(t / 3600), (double)(t % 3600 / 60));
    if (t >= 60) return format("%.0f min %02.0f s", (double)(t / 60), (double)(t % 60));
    return format("%.0f s", (double)t);
}

std::string bytes(size_t b) {
    return b >= (size_t(1) << 30) ? format("%.2f GiB", (double)b / (1 << 30)) : format("%.1f MiB", (double)b / (1 << 20));
}

}  // namespace

size_t peakHostResidentBytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return (size_t)u.ru_maxrss * 1024;  // KiB on Linux
}

std::string ProgressReporter::progressLine(const RunProgress& p) {
    const double done = (double)p.stepsDone, total = (double)p.stepsTotal;
    std::string s = "[deme] t = " + format("%.6g", p.simTime) + " of " + format("%.6g", p.simTimeEnd) + " s (" +
                    format("%.1f", total > 0 ? 100.0 * done / total : 100.0) + " %), ";
    s += format("%.3g", p.wallSeconds > 0 ? (double)p.spheres * done / p.wallSeconds : 0.0) + " sphere-steps/s, ETA ";
    s += done > 0 ? duration(p.wallSeconds * (total - done) / done) : std::string("unknown");
    return s;
}

std::string ProgressReporter::summaryLine(const RunSummary& r, bool stoppedEarly) {
    std::string s = "[deme] run" + std::string(stoppedEarly ? " (stopped early)" : "") + ": " +
                    format("%.6g", r.simSeconds) + " s simulated in " + format("%.3g", r.wallSeconds) +
                    " s wall, " + std::to_string(r.steps) + " steps, " + format("%.3g", r.sphereStepsPerSecond) +
                    " sphere-steps/s, " + format("%.3g", r.contactsPerSphere) + " contacts/sphere, peak host memory " +
                    bytes(r.peakHostBytes);
    if (r.onGpu) s += ", GPU memory " + bytes(r.deviceBytes) + " (at most " + bytes(r.deviceBytesPeak) + ")";
    return s;
}

void ProgressReporter::onProgress(const RunProgress& p, Verbosity level, const std::function<RunSummary()>& summary) {
    if (!m_inCall) {  // the first poll of a call
        m_inCall = true;
        m_printed = false;
        m_lastLine = 0.0;
        m_lastLength = 0;
    }
    const bool speak = m_enabled && level >= Verbosity::INFO;
    if (!p.finished) {
        if (!speak || p.wallSeconds < m_interval || (m_printed && p.wallSeconds - m_lastLine < m_interval)) return;
        const std::string line = progressLine(p);
        if (m_redraw) {
            // Spaces over the rest of a longer previous line.
            m_out << '\r' << line << std::string(m_lastLength > line.size() ? m_lastLength - line.size() : 0, ' ');
        } else {
            m_out << line << '\n';
        }
        m_out.flush();
        m_lastLength = line.size();
        m_lastLine = p.wallSeconds;
        m_printed = true;
        return;
    }
    m_inCall = false;
    if (!speak) return;
    if (m_printed && m_redraw) {  // the redrawn line ends at the call's last state
        const std::string line = progressLine(p);
        m_out << '\r' << line << std::string(m_lastLength > line.size() ? m_lastLength - line.size() : 0, ' ') << '\n';
    }
    if (p.wallSeconds >= m_interval && summary)
        m_out << summaryLine(summary(), p.stepsDone < p.stepsTotal) << '\n';
    m_out.flush();
}

}  // namespace deme
