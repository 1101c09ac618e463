// Helpers for the benchmark programs: wall clock, peak memory, machine name, JSON output.
#pragma once

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <sys/resource.h>

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

  private:
    JsonLine& raw(const std::string& k, const std::string& v) {
        if (!m_body.empty()) m_body += ", ";
        m_body += "\"" + k + "\": " + v;
        return *this;
    }
    std::string m_body;
};

}  // namespace deme_bench
