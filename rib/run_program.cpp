// run_program.cpp: RunProgram's helper process (run_program.h), with fork/exec, pipes
// and poll so that its time and its output stay bounded.
#include "run_program.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>

namespace rib {

namespace {
// Stops the child (and what its shell started: its process group) if it still runs, and
// collects it; its wait status, or -1.
int finish(pid_t pid, bool stop) {
    if (stop && kill(-pid, SIGKILL) != 0) kill(pid, SIGKILL);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return -1;
    return status;
}
}  // namespace

bool runProgram(const std::string& command, const std::string& request,
                const RunProgramLimits& limits, std::string* rib, std::string* why) {
    int in[2], out[2];
    if (pipe(in) != 0) return *why = std::string("pipe: ") + std::strerror(errno), false;
    if (pipe(out) != 0) {
        close(in[0]), close(in[1]);
        return *why = std::string("pipe: ") + std::strerror(errno), false;
    }
    const pid_t pid = fork();
    if (pid < 0) {
        for (int fd : {in[0], in[1], out[0], out[1]}) close(fd);
        return *why = std::string("fork: ") + std::strerror(errno), false;
    }
    if (pid == 0) {  // the child: the pipes as its standard input and output
        setpgid(0, 0);
        dup2(in[0], 0), dup2(out[1], 1);
        for (int fd : {in[0], in[1], out[0], out[1]}) close(fd);
        execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    setpgid(pid, pid);  // (as the child does: whichever runs first)
    close(in[0]), close(out[1]);
    // The request, then end of input: one answer is all that is asked.
    const std::string line = request + "\n";
    void (*pipeHandler)(int) = signal(SIGPIPE, SIG_IGN);  // (a program that never reads)
    for (size_t sent = 0; sent < line.size();) {
        const ssize_t n = write(in[1], line.data() + sent, line.size() - sent);
        if (n <= 0) break;
        sent += size_t(n);
    }
    close(in[1]);
    signal(SIGPIPE, pipeHandler);
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(limits.seconds);
    rib->clear();
    bool answered = false, closed = false;
    char buf[65536];
    while (!answered && !closed) {
        const double left =
            std::chrono::duration<double>(deadline - std::chrono::steady_clock::now())
                .count();
        if (left <= 0) {
            close(out[0]);
            finish(pid, true);
            std::ostringstream s;
            s << "no answer within " << limits.seconds << " s (stopped)";
            *why = s.str();
            return false;
        }
        pollfd p{out[0], POLLIN, 0};
        const int ready = poll(&p, 1, int(std::min(left, 1.0) * 1000) + 1);
        if (ready < 0 && errno != EINTR) break;
        if (ready <= 0) continue;
        const ssize_t n = read(out[0], buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            closed = true;
            break;
        }
        const void* end = std::memchr(buf, 0377, size_t(n));
        const size_t take = end ? size_t(static_cast<const char*>(end) - buf) : size_t(n);
        if (rib->size() + take > limits.maxBytes) {
            close(out[0]);
            finish(pid, true);
            *why = "more than " + std::to_string(limits.maxBytes) +
                   " bytes of output (stopped)";
            return false;
        }
        rib->append(buf, take);
        answered = end != nullptr;
    }
    close(out[0]);
    // Answered: it may wait for the next request, which will not come; else it has ended
    // (a program that ends well without the 0377 byte answered with all it wrote).
    const int status = finish(pid, answered);
    if (answered || (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0))
        return true;
    if (status != -1 && WIFEXITED(status))
        *why = "failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")";
    else if (status != -1 && WIFSIGNALED(status))
        *why = "killed by signal " + std::to_string(WTERMSIG(status));
    else
        *why = "could not be waited for";
    return false;
}

namespace {
DynamicLoader g_dynamicLoader = nullptr;
}  // namespace
void setDynamicLoader(DynamicLoader loader) {
    g_dynamicLoader = loader;
}
DynamicLoader dynamicLoader() {
    return g_dynamicLoader;
}

}  // namespace rib
