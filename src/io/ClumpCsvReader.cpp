#include "io/ClumpCsvReader.h"

#include <deme/Error.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace deme {
namespace {

// Strips spaces, tabs and a stray '\r' (Windows line endings) from both ends.
std::string trim(const std::string& s) {
    const char* ws = " \t\r\n\f\v";
    size_t b = s.find_first_not_of(ws);
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(ws) - b + 1);
}

std::vector<std::string> splitCsv(const std::string& line) {
    std::vector<std::string> out;
    size_t pos = 0;
    while (true) {
        size_t comma = line.find(',', pos);
        out.push_back(trim(line.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos)));
        if (comma == std::string::npos) return out;
        pos = comma + 1;
    }
}

std::string lower(std::string s) {
    for (char& ch : s) ch = (char)std::tolower((unsigned char)ch);
    return s;
}

}  // namespace

ClumpSpheres readClumpCsv(const std::string& path, const std::string& call) {
    std::ifstream in(path);
    if (!in.is_open()) throwFileError(call, path, 0, "cannot open file");

    static const char* kNames[4] = {"x", "y", "z", "r"};
    int col[4] = {-1, -1, -1, -1};  // column index of x, y, z, r
    size_t nfields = 0, header_line = 0, line_no = 0;
    ClumpSpheres out;
    std::string raw;

    while (std::getline(in, raw)) {
        line_no++;
        if (line_no == 1 && raw.compare(0, 3, "\xEF\xBB\xBF") == 0) raw.erase(0, 3);  // UTF-8 BOM
        const std::string line = trim(raw);
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> fields = splitCsv(line);

        if (header_line == 0) {
            header_line = line_no;
            nfields = fields.size();
            for (size_t i = 0; i < fields.size(); i++) {
                const std::string name = lower(fields[i]);
                for (int k = 0; k < 4; k++) {
                    if (name != kNames[k]) continue;
                    if (col[k] >= 0)
                        throwFileError(call, path, line_no, std::string("header repeats column '") + kNames[k] + "'");
                    col[k] = (int)i;
                }
            }
            for (int k = 0; k < 4; k++)
                if (col[k] < 0)
                    throwFileError(call, path, line_no,
                                   std::string("header row lacks column '") + kNames[k] +
                                       "' (expected a header naming columns x,y,z,r)");
            continue;
        }

        if (fields.size() != nfields)
            throwFileError(call, path, line_no,
                           "expected " + std::to_string(nfields) + " fields, got " + std::to_string(fields.size()));
        float v[4];
        for (int k = 0; k < 4; k++) {
            const std::string& f = fields[col[k]];
            char* end = nullptr;
            errno = 0;
            const double d = f.empty() ? 0.0 : std::strtod(f.c_str(), &end);
            if (f.empty() || end != f.c_str() + f.size())
                throwFileError(call, path, line_no,
                               std::string("column '") + kNames[k] + "': '" + f + "' is not a number");
            // Checking after the float cast also rejects values that overflow float (e.g. 1e300).
            v[k] = (float)d;
            if (!std::isfinite(d) || !std::isfinite(v[k]))
                throwFileError(call, path, line_no,
                               std::string("column '") + kNames[k] + "': '" + f + "' is not finite");
        }
        if (!(v[3] > 0.f)) throwFileError(call, path, line_no, "radius must be positive, got " + fields[col[3]]);
        out.positions.push_back(make_float3(v[0], v[1], v[2]));
        out.radii.push_back(v[3]);
    }
    // getline stops on EOF (eofbit) or on a read failure such as a directory path (badbit).
    if (in.bad()) throwFileError(call, path, 0, "read error");
    if (header_line == 0) throwFileError(call, path, line_no, "no header row (expected columns x,y,z,r)");
    if (out.radii.empty()) throwFileError(call, path, header_line, "no spheres after the header");
    return out;
}

}  // namespace deme
