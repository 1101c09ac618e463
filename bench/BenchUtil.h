// Helpers for the benchmark programs: wall clock, peak memory, machine name, JSON output.
#pragma once

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <sys/resource.h>

#include <deme/MemoryStats.h>
#include <deme/RunSummary.h>

namespace deme_bench {

inline double seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

inline double peakMemoryMiB() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return (double)u.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

inline std::string cpuName() {
    std::ifstream f("/proc/cpuinfo");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

// Minimal JSON object builder: one line, keys in insertion order.
class JsonLine {
  public:
    JsonLine& add(const std::string& k, const std::string& v) { return raw(k, "\"" + v + "\""); }
    JsonLine& add(const std::string& k, const char* v) { return add(k, std::string(v)); }
    JsonLine& add(const std::string& k, double v) {
        std::ostringstream os;
        os.precision(6);
        os << v;
        return raw(k, os.str());
    }
    std::string str() const { return "{" + m_body + "}"; }
    bool has(const std::string& k) const { return m_body.find("\"" + k + "\": ") != std::string::npos; }

  private:
    JsonLine& raw(const std::string& k, const std::string& v) {
        if (!m_body.empty()) m_body += ", ";
        m_body += "\"" + k + "\": " + v;
        return *this;
    }
    std::string m_body;
};

// The run summary's figures (DEMSolver::GetRunSummary, of the last DoDynamics / DoStepDynamics
// call) under the keys every benchmark shares; a key the benchmark set itself (its own timed loop's
// wall time and steps) is kept as it is.
inline void addRunSummary(JsonLine& j, const deme::RunSummary& r) {
    if (!j.has("wall_s")) j.add("wall_s", r.wallSeconds);
    if (!j.has("steps")) j.add("steps", (double)r.steps);
    if (!j.has("sphere_steps_per_s")) j.add("sphere_steps_per_s", r.sphereStepsPerSecond);
    if (!j.has("contacts_per_sphere")) j.add("contacts_per_sphere", r.contactsPerSphere);
    j.add("peak_host_rss_mib", (double)r.peakHostBytes / (1 << 20));
    j.add("device_bytes", (double)r.deviceBytes).add("device_peak_bytes", (double)r.deviceBytesPeak);
}

// A case's JSON line, with the run summary's keys (addRunSummary), on stdout at once; with
// DEME_BENCH_TIMING set, the solver's phase timings and its threads' collaboration after it.
template <class Solver>
void printCase(JsonLine& j, const Solver& sim) {
    addRunSummary(j, sim.GetRunSummary());
    std::printf("%s\n", j.str().c_str());
    std::fflush(stdout);
    if (std::getenv("DEME_BENCH_TIMING")) {
        sim.ShowTimingStats();
        sim.ShowThreadCollaborationStats();
    }
}

// The solver's memory by group (DEMSolver::GetMemoryStats): totals and bytes per sphere, device
// and host, and each group's bytes per sphere ("mem_<device|host>_<group>_per_sphere").
inline void addMemoryStats(JsonLine& j, const deme::MemoryStats& m) {
    const double n = m.spheres ? (double)m.spheres : 1.0;
    j.add("mem_device_bytes", (double)m.deviceTotal()).add("mem_host_bytes", (double)m.hostTotal());
    j.add("mem_estimate_bytes", (double)m.estimatedTotal()).add("mem_estimated_pairs", (double)m.estimatedPairs);
    for (int g = 0; g < deme::NUM_MEMORY_GROUPS; g++) {
        const std::string key = deme::memoryGroupKey((deme::MemoryGroup)g);
        j.add("mem_device_" + key + "_per_sphere", (double)m.deviceBytes[g] / n);
        j.add("mem_device_peak_" + key + "_per_sphere", (double)m.devicePeakBytes[g] / n);
        j.add("mem_host_" + key + "_per_sphere", (double)m.hostBytes[g] / n);
        j.add("mem_estimate_" + key + "_per_sphere", (double)m.estimatedBytes[g] / n);
    }
}

}  // namespace deme_bench
