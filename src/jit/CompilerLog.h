// Trimming a compiler's output for an error message (host compiler and NVRTC alike).
#pragma once

#include <sstream>
#include <string>

namespace deme::jit {

// The first maxLines lines of text, and a note of how many more there were.
inline std::string firstLines(const std::string& text, size_t maxLines) {
    std::istringstream in(text);
    std::string out, line;
    size_t n = 0, total = 0;
    while (std::getline(in, line)) {
        if (n < maxLines) {
            out += line + "\n";
            n++;
        }
        total++;
    }
    if (total > n) out += "[... " + std::to_string(total - n) + " more lines]\n";
    return out;
}

// NVRTC's locations ("force_model(3): error: ...") in the host compiler's form ("force_model:3: error:
// ..."), so that a force model's compile error reads the same on either backend.
inline std::string gccStyleLocations(const std::string& text) {
    std::istringstream in(text);
    std::string out, line;
    bool first = true;
    while (std::getline(in, line)) {
        const size_t open = line.find('(');
        const size_t close = open == std::string::npos ? std::string::npos : line.find("): ", open);
        bool digits = close != std::string::npos && close > open + 1 && open > 0;
        for (size_t k = open + 1; digits && k < close; k++) digits = line[k] >= '0' && line[k] <= '9';
        if (digits)
            line = line.substr(0, open) + ":" + line.substr(open + 1, close - open - 1) + ":" + line.substr(close + 2);
        out += (first ? "" : "\n") + line;
        first = false;
    }
    return out;
}

}  // namespace deme::jit
