#include "child_process.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace chainbench {
namespace {

bool read_all(int fd, void* data, std::size_t size) {
  auto* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t got = read(fd, p, size);
    if (got <= 0) return false;
    p += got, size -= static_cast<std::size_t>(got);
  }
  return true;
}

}  // namespace

ChildOutcome run_in_child(const std::function<void(void* result)>& work, void* result,
                          std::size_t size, double timeout_s) {
  ChildOutcome outcome;
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("run_in_child: pipe() failed");
  std::fflush(nullptr);  // nothing buffered may be written twice
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error("run_in_child: fork() failed");
  }
  if (pid == 0) {
    close(fds[0]);
    work(result);  // the child's own copy of the caller's memory
    const ssize_t wrote = write(fds[1], result, size);
    _exit(wrote == static_cast<ssize_t>(size) ? 0 : 3);
  }
  close(fds[1]);
  // The child writes its result in one go at its very end, so the first readable byte (or the
  // end of the pipe, if it died) comes when it is done.
  pollfd p{fds[0], POLLIN, 0};
  const int ready = poll(&p, 1, static_cast<int>(timeout_s * 1000.0));
  std::vector<char> bytes(size);
  if (ready <= 0) {
    kill(pid, SIGKILL);
    outcome.hang = true;
  } else {
    outcome.finished = read_all(fds[0], bytes.data(), size);
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  outcome.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (outcome.hang) return outcome;
  if (WIFSIGNALED(status)) {
    outcome.finished = false;
    outcome.signal = WTERMSIG(status);
  } else if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
    outcome.finished = false;
    outcome.exit_status = WEXITSTATUS(status);
  }
  if (outcome.finished) std::copy(bytes.begin(), bytes.end(), static_cast<char*>(result));
  return outcome;
}

}  // namespace chainbench
