#include "child_process.h"

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

namespace chainbench {
namespace {

using Clock = std::chrono::steady_clock;

bool write_all(int fd, const char* p, std::size_t size) {
  while (size > 0) {
    const ssize_t wrote = write(fd, p, size);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return false;
    p += wrote, size -= static_cast<std::size_t>(wrote);
  }
  return true;
}

}  // namespace

ChildOutcome run_in_child_bytes(const std::function<std::string()>& work, std::string& result,
                                double timeout_s, const std::atomic<bool>* stop) {
  ChildOutcome outcome;
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("run_in_child: pipe() failed");
  std::fflush(nullptr);  // nothing buffered may be written twice
  const auto t0 = Clock::now();
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error("run_in_child: fork() failed");
  }
  if (pid == 0) {
    close(fds[0]);
    // Ctrl-C ends the child; the caller's handlers (which keep what finished, or remove its
    // temporary files) are the caller's alone.
    for (const int sig : {SIGINT, SIGTERM, SIGHUP})
      signal(sig, SIG_DFL);
    // A caller killed outright takes its child along: a hung plugin must not outlive it.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(4);
    const std::string bytes = work();  // the child's own copy of the caller's memory
    // The length first, so that a result cut short is told from a whole one.
    const std::uint64_t size = bytes.size();
    const bool ok = write_all(fds[1], reinterpret_cast<const char*>(&size), sizeof size) &&
                    write_all(fds[1], bytes.data(), bytes.size());
    _exit(ok ? 0 : 3);
  }
  close(fds[1]);
  // Read as the bytes come (a result may be larger than the pipe holds) until the child closes
  // its end, the time is up, or the caller is stopped.
  const auto deadline = t0 + std::chrono::duration<double>(timeout_s);
  std::string bytes;
  char buffer[65536];
  bool eof = false;
  while (!eof) {
    const auto now = Clock::now();
    if (now >= deadline) {
      outcome.hang = true;
      break;
    }
    if (stop && stop->load()) {
      outcome.interrupted = true;
      break;
    }
    // Wake now and then to look at the stop flag.
    // In double: with no time limit the deadline is infinitely far.
    const double left_ms = std::chrono::duration<double, std::milli>(deadline - now).count();
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, left_ms >= 100.0 ? 100 : static_cast<int>(left_ms) + 1);
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t got = read(fds[0], buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      eof = true;
    } else {
      bytes.append(buffer, static_cast<std::size_t>(got));
    }
  }
  if (!eof) kill(pid, SIGKILL);
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  outcome.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!eof) return outcome;
  if (WIFSIGNALED(status)) {
    outcome.signal = WTERMSIG(status);
    if (stop && stop->load() && outcome.signal == SIGINT) outcome.interrupted = true;
    return outcome;
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
    outcome.exit_status = WEXITSTATUS(status);
    return outcome;
  }
  std::uint64_t size = 0;
  if (bytes.size() < sizeof size) return outcome;  // exited (status 0) before its result
  std::memcpy(&size, bytes.data(), sizeof size);
  if (bytes.size() - sizeof size != size) return outcome;
  result = bytes.substr(sizeof size);
  outcome.finished = true;
  return outcome;
}

std::string child_failure(const ChildOutcome& o, double timeout_s) {
  if (o.hang) {
    char text[64];
    std::snprintf(text, sizeof text, "ran out of time (%g s)", timeout_s);
    return text;
  }
  if (o.interrupted) return "interrupted";
  if (o.signal != 0) {
    const char* name = sigabbrev_np(o.signal);
    return "died of signal " + std::to_string(o.signal) +
           (name ? std::string(" (SIG") + name + ")" : std::string());
  }
  return "exited with status " + std::to_string(o.exit_status) + " and no result";
}

}  // namespace chainbench
