// A ParaView collection (.pvd): the frames of one series with the simulated time of each, so that
// ParaView opens one file and plays the run with its real time axis. Rewritten (to a temporary
// name, then renamed) each time a frame is added, so it always lists exactly the frames written so
// far, also when the run stops early.
#pragma once

#include <string>
#include <vector>

namespace deme {

class PvdSeries {
  public:
    explicit PvdSeries(std::string pvdPath) : m_path(std::move(pvdPath)) {}
    // Adds the frame (or updates the time of one of the same file), then rewrites the .pvd. Frames
    // are listed by their path relative to the .pvd's folder. Throws deme::Error naming `call`.
    void add(const std::string& framePath, double time, const std::string& call);
    const std::string& path() const { return m_path; }
    size_t size() const { return m_entries.size(); }

  private:
    struct Entry {
        std::string file;
        double time;
    };
    void write(const std::string& call) const;
    std::string m_path;
    std::vector<Entry> m_entries;
};

}  // namespace deme
