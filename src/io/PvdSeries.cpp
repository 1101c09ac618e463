#include "io/PvdSeries.h"

#include <charconv>
#include <filesystem>

#include "io/AtomicFile.h"

namespace deme {

namespace fs = std::filesystem;

namespace {

std::string xmlEscaped(const std::string& s) {
    std::string o;
    for (char c : s) {
        switch (c) {
        case '&': o += "&amp;"; break;
        case '<': o += "&lt;"; break;
        case '>': o += "&gt;"; break;
        case '"': o += "&quot;"; break;
        case '\'': o += "&apos;"; break;
        default: o += c;
        }
    }
    return o;
}

// The shortest text that reads back as the same double.
std::string exact(double v) {
    char b[32];
    return std::string(b, std::to_chars(b, b + sizeof b, v).ptr);
}

}  // namespace

void PvdSeries::add(const std::string& framePath, double time, const std::string& call) {
    std::error_code ec;
    const fs::path base = fs::absolute(fs::path(m_path), ec).parent_path();
    const fs::path frame = fs::absolute(fs::path(framePath), ec);
    std::string rel = frame.lexically_normal().lexically_relative(base.lexically_normal()).generic_string();
    if (rel.empty()) rel = frame.generic_string();
    bool found = false;
    for (Entry& e : m_entries)
        if (e.file == rel) {
            e.time = time;
            found = true;
        }
    if (!found) m_entries.push_back({rel, time});
    write(call);
}

void PvdSeries::write(const std::string& call) const {
    std::string s = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const Entry& e : m_entries)
        s += "    <DataSet timestep=\"" + exact(e.time) + "\" group=\"\" part=\"0\" file=\"" + xmlEscaped(e.file) +
             "\"/>\n";
    s += "  </Collection>\n</VTKFile>\n";
    AtomicFile f(m_path, call);
    f.write(s);
    f.commit();
}

}  // namespace deme
