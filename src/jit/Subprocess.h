// Runs a program and collects what it prints; used to call compilers at run time.
#pragma once

#include <string>
#include <vector>

namespace deme::jit {

struct ProcessResult {
    int exitCode = -1;   // the exit status, or -1 if a signal ended the process
    int signal = 0;      // the signal that ended it, if any
    std::string output;  // stdout and stderr interleaved, as a terminal would show them
    bool succeeded() const { return exitCode == 0; }
};

// Runs argv[0] (looked up in PATH) with the given arguments and this process's environment, without
// a shell, so arguments need no quoting. Throws deme::Error naming `call` if it cannot be started.
ProcessResult runCapturingOutput(const std::string& call, const std::vector<std::string>& argv);

}  // namespace deme::jit
