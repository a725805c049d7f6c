// SPDX-License-Identifier: MIT
#include "support/child_process.h"
#include "support/number_text.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace chainbench {
namespace {

using Clock = std::chrono::steady_clock;

// The child's mark (child_mark()), in memory shared with the parent; null outside a child.
std::atomic<int>* g_mark = nullptr;

bool write_all(int fd, const char* p, std::size_t size) {
  while (size > 0) {
    const ssize_t wrote = write(fd, p, size);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return false;
    p += wrote, size -= static_cast<std::size_t>(wrote);
  }
  return true;
}

// Every descriptor but stdin, stdout, stderr and `keep` closed: the child must not reach the
// caller's files (its outputs' temporaries above all).
void close_inherited(int keep) {
  auto close_from = [](unsigned first, unsigned last) {
    if (first > last) return;
#ifdef SYS_close_range
    if (syscall(SYS_close_range, first, last, 0) == 0) return;
#endif
    const long open_max = sysconf(_SC_OPEN_MAX);
    const unsigned end = static_cast<unsigned>(
        std::min<long>(open_max > 0 ? open_max : 65536, static_cast<long>(last) + 1));
    for (unsigned fd = first; fd < end; ++fd)
      close(static_cast<int>(fd));
  };
  close_from(3, static_cast<unsigned>(keep) - 1);
  close_from(static_cast<unsigned>(keep) + 1, ~0u);
}

// A process id as a descriptor that becomes readable when the process ends, or -1 (kernels
// before 5.3): the parent then looks every few milliseconds.
int open_pidfd(pid_t pid) {
#ifdef SYS_pidfd_open
  return static_cast<int>(syscall(SYS_pidfd_open, pid, 0));
#else
  (void)pid;
  return -1;
#endif
}

void read_available(int fd, std::string& bytes, bool& eof) {
  char buffer[65536];
  for (;;) {
    const ssize_t got = read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got == 0) eof = true;
    if (got <= 0) return;  // EAGAIN: nothing more now
    bytes.append(buffer, static_cast<std::size_t>(got));
  }
}

}  // namespace

bool under_sanitizer() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
  return true;
#else
  return false;
#endif
#else
  return false;
#endif
}

std::uint64_t child_memory_cap() {
  if (under_sanitizer()) return 0;  // the sanitizers reserve terabytes of address space
  if (const char* mb = std::getenv("CHAINBENCH_CHILD_MEMORY_MB")) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(mb, &end, 10);
    if (end != mb && *end == '\0' && v > 0 && v < (1ull << 40)) return v << 20;
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const std::uint64_t physical =
      pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page)
                            : 0;
  return std::max<std::uint64_t>(physical / 2, std::uint64_t{2} << 30);
}

std::atomic<int>* child_mark() {
  return g_mark;
}

ChildOutcome run_in_child_bytes(const std::function<std::string()>& work, std::string& result,
                                double timeout_s, const std::atomic<bool>* stop) {
  ChildOutcome outcome;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("run_in_child: pipe() failed");
  void* shared = mmap(nullptr, sizeof(std::atomic<int>), PROT_READ | PROT_WRITE,
                      MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error("run_in_child: mmap() failed");
  }
  auto* mark = new (shared) std::atomic<int>(-1);
  const std::uint64_t cap = child_memory_cap();
  outcome.memory_cap = cap;
  std::fflush(nullptr);  // nothing buffered may be written twice
  const auto t0 = Clock::now();
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    munmap(shared, sizeof(std::atomic<int>));
    throw std::runtime_error("run_in_child: fork() failed");
  }
  if (pid == 0) {
    close(fds[0]);
    setpgid(0, 0);  // a group of its own, so that a timeout kills whatever it started
    // Ctrl-C ends the child; the caller's handlers (which keep what finished, or remove its
    // temporary files) are the caller's alone.
    for (const int sig : {SIGINT, SIGTERM, SIGHUP})
      signal(sig, SIG_DFL);
    // A caller killed outright takes its child along: a hung plugin must not outlive it.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(4);
    close_inherited(fds[1]);
    // Its own process group is not the terminal's: a read of the terminal would stop it, so its
    // stdin is empty instead.
    if (const int null = open("/dev/null", O_RDONLY); null >= 0 && null != 0) {
      dup2(null, 0);
      close(null);
    }
    if (cap > 0) {
      const rlimit limit{cap, cap};
      setrlimit(RLIMIT_AS, &limit);
    }
    g_mark = mark;
    const std::string bytes = work();  // the child's own copy of the caller's memory
    // The length first, so that a result cut short is told from a whole one.
    const std::uint64_t size = bytes.size();
    const bool ok = write_all(fds[1], reinterpret_cast<const char*>(&size), sizeof size) &&
                    write_all(fds[1], bytes.data(), bytes.size());
    _exit(ok ? 0 : 3);
  }
  setpgid(pid, pid);  // as the child does, whichever runs first
  close(fds[1]);
  fcntl(fds[0], F_SETFL, fcntl(fds[0], F_GETFL) | O_NONBLOCK);
  const int pidfd = open_pidfd(pid);
  // Read as the bytes come (a result may be larger than the pipe holds) until the child ends,
  // the time is up, or the caller is stopped. The pipe's end alone decides nothing: a plugin may
  // close it early, or leave a process of its own holding it open.
  const auto deadline = t0 + std::chrono::duration<double>(timeout_s);
  std::string bytes;
  bool eof = false, ended = false;
  int status = 0;
  rusage usage{};
  for (;;) {
    // Ended, and not yet reaped: its group is killed first, while its id is still its own.
    siginfo_t info{};
    if (waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        info.si_pid == pid) {
      ended = true;
      break;
    }
    const auto now = Clock::now();
    if (now >= deadline) {
      outcome.hang = true;
      break;
    }
    if (stop && stop->load()) {
      outcome.interrupted = true;
      break;
    }
    // Wake now and then to look at the stop flag; in double, since with no time limit the
    // deadline is infinitely far.
    const double left_ms = std::chrono::duration<double, std::milli>(deadline - now).count();
    const int wait_ms = pidfd >= 0 ? 100 : 5;
    pollfd p[2] = {{eof ? -1 : fds[0], POLLIN, 0}, {pidfd, POLLIN, 0}};
    const int ready = poll(p, 2, left_ms >= wait_ms ? wait_ms : static_cast<int>(left_ms) + 1);
    if (ready > 0 && !eof && (p[0].revents & (POLLIN | POLLHUP | POLLERR)))
      read_available(fds[0], bytes, eof);
  }
  kill(-pid, SIGKILL);  // the child's whole group: what it started, or left behind
  kill(pid, SIGKILL);   // (should it have left the group)
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  if (ended && !eof) read_available(fds[0], bytes, eof);  // all it wrote is in the pipe now
  if (pidfd >= 0) close(pidfd);
  close(fds[0]);
  outcome.mark = mark->load();
  munmap(shared, sizeof(std::atomic<int>));
  outcome.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!ended) return outcome;
  // Near its cap: a child that died of it ran out of memory (malloc failed, or new threw).
  const std::uint64_t peak = static_cast<std::uint64_t>(std::max(0L, usage.ru_maxrss)) * 1024;
  outcome.out_of_memory = cap > 0 && peak >= cap / 4 * 3;
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
  outcome.out_of_memory = false;
  return outcome;
}

std::string signal_text(int signal) {
  const char* name = sigabbrev_np(signal);
  return "signal " + std::to_string(signal) +
         (name ? std::string(" (SIG") + name + ")" : std::string());
}

std::string child_failure(const ChildOutcome& o, double timeout_s, const std::string& where) {
  std::string why;
  if (o.hang) {
    why = "ran out of time (";
    why += exact_number(timeout_s);
    why += " s)";
  } else if (o.interrupted) {
    return "interrupted";
  } else if (o.signal != 0) {
    why = "died of " + signal_text(o.signal);
  } else {
    why = "exited with status " + std::to_string(o.exit_status) + " and no result";
  }
  why += where;
  if (o.out_of_memory) {
    why += ": out of memory (its cap is " + std::to_string(o.memory_cap >> 20) +
           " MiB of address space)";
  }
  return why;
}

}  // namespace chainbench
