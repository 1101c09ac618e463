// Runs one of the Python check scripts of tests/python/ with Debian's /usr/bin/python3 (the one with
// python3-meshio and python3-pil, which scripts/setup.sh installs; DEME_TEST_PYTHON names another, as
// tests/gpu/run.sh does on a GPU machine without them) and returns its exit status and output, for the
// tests that have files read back by readers the engine has no part in.
#pragma once

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/wait.h>

namespace deme_test {

struct ScriptResult {
    int status = -1;
    std::string output;
};

inline ScriptResult runPythonCheck(const std::string& script, const std::string& args) {
    const char* python = std::getenv("DEME_TEST_PYTHON");
    const std::string cmd = std::string(python && *python ? python : "/usr/bin/python3") +
                            " " DEME_TEST_SOURCE_DIR "/python/" + script + " " + args + " 2>&1";
    ScriptResult r;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
    const int st = pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

// Arguments are paths made by the tests (no quotes or spaces in them); times go as exact decimals.
inline std::string exactNumber(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

}  // namespace deme_test
