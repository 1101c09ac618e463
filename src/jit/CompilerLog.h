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

}  // namespace deme::jit
