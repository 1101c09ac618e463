#include "jit/Subprocess.h"

#include <deme/Error.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

extern char** environ;

namespace deme::jit {

namespace {

// Closes the descriptors on every path out, exceptions included.
struct Pipe {
    int fd[2] = {-1, -1};
    ~Pipe() {
        for (int f : fd)
            if (f >= 0) close(f);
    }
    void closeEnd(int i) {
        close(fd[i]);
        fd[i] = -1;
    }
};

struct SpawnActions {
    posix_spawn_file_actions_t actions;
    SpawnActions() { posix_spawn_file_actions_init(&actions); }
    ~SpawnActions() { posix_spawn_file_actions_destroy(&actions); }
};

}  // namespace

ProcessResult runCapturingOutput(const std::string& call, const std::vector<std::string>& argv) {
    if (argv.empty()) throwError(call, "no program to run");
    // Close-on-exec, so that a child another thread starts meanwhile does not inherit the write end
    // and keep our read from ever seeing end-of-file. dup2 in the child clears the flag on 1 and 2.
    Pipe pipe;
    if (pipe2(pipe.fd, O_CLOEXEC) != 0) throwError(call, std::string("cannot create a pipe: ") + std::strerror(errno));
    SpawnActions sa;
    posix_spawn_file_actions_addopen(&sa.actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&sa.actions, pipe.fd[1], 1);
    posix_spawn_file_actions_adddup2(&sa.actions, pipe.fd[1], 2);

    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    const int err = posix_spawnp(&pid, args[0], &sa.actions, nullptr, args.data(), environ);
    if (err != 0) throwError(call, "cannot run '" + argv[0] + "': " + std::strerror(err));
    pipe.closeEnd(1);

    ProcessResult result;
    char buffer[4096];
    for (;;) {
        const ssize_t n = read(pipe.fd[0], buffer, sizeof buffer);
        if (n > 0) {
            result.output.append(buffer, (size_t)n);
        } else if (n == 0 || errno != EINTR) {
            break;
        }
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) throwError(call, "lost track of '" + argv[0] + "': " + std::strerror(errno));
    }
    if (WIFEXITED(status)) {
        result.exitCode = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
        result.signal = WTERMSIG(status);
    }
    return result;
}

}  // namespace deme::jit
