// SPDX-License-Identifier: MIT
#include "support/output_file.h"

#include "support/input_error.h"
#include "support/text_table.h"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>

namespace chainbench {
namespace {

namespace fs = std::filesystem;

// The temporaries not yet committed, for the signal handler to remove: plain C strings in a fixed
// table, so that the handler reads them without allocating or locking.
constexpr std::size_t kMaxTemporaries = 16;
std::array<std::atomic<char*>, kMaxTemporaries> g_temporaries{};

extern "C" void remove_temporaries(int sig) {
  for (std::atomic<char*>& slot : g_temporaries) {
    if (char* path = slot.load()) unlink(path);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// The handler stands for SIGINT, SIGTERM and SIGHUP from the first output on; a command that
// catches SIGINT itself (to keep what finished) restores it when done.
void install_handler() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
      // A signal the caller ignores (nohup) stays ignored.
      if (std::signal(sig, remove_temporaries) == SIG_IGN) std::signal(sig, SIG_IGN);
    }
  });
}

int remember(const std::string& temp) {
  for (std::size_t k = 0; k < kMaxTemporaries; ++k) {
    char* expected = nullptr;
    char* copy = strdup(temp.c_str());
    if (g_temporaries[k].compare_exchange_strong(expected, copy)) return static_cast<int>(k);
    std::free(copy);
  }
  return -1;  // more outputs than the table holds: this one is removed on errors, not on signals
}

void forget(int slot) {
  if (slot < 0) return;
  char* path = g_temporaries[static_cast<std::size_t>(slot)].exchange(nullptr);
  std::free(path);
}

// Why `path` cannot be written: the folder that is not there, a folder where a file should be,
// or the system's reason.
std::string why_not(const std::string& path, int error) {
  std::error_code ec;
  const fs::path p(path);
  if (fs::is_directory(p, ec)) return "is a directory";
  if (const fs::path dir = p.parent_path(); !dir.empty() && !fs::is_directory(dir, ec))
    return "no such directory " + dir.string();
  return error != 0 ? std::strerror(error) : "cannot be opened";
}

// Where a name that does not exist leads: a symbolic link to nowhere is followed, link by link
// (at most 40, as the system does), to the file it would make; any other name is itself.
std::string dangling_target(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::absolute(path, ec);
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    const fs::path next = fs::read_symlink(p, ec);
    if (ec) break;
    p = next.is_absolute() ? next : p.parent_path() / next;
  }
  return fs::weakly_canonical(p, ec).string();
}

}  // namespace

OutputFile::OutputFile(const std::string& path, const char* option) : path_(path), target_(path) {
  if (path == "-") {
    throw InputError(std::string(option) +
                     " -: standard output carries the table; give a file name (/dev/stdout works)");
  }
  struct stat st {};
  const bool exists = stat(path.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode))
    throw InputError(std::string(option) + ": cannot write " + path + ": is a directory");
  errno = 0;
  // Where the name leads: a symbolic link keeps pointing where it did, so the file it names is
  // what is written, whether or not it exists yet.
  std::error_code ec;
  const std::string leads_to = exists ? fs::canonical(path, ec).string() : dangling_target(path);
  auto under_system = [](const std::string& p) {
    return p.rfind("/dev/", 0) == 0 || p.rfind("/proc/", 0) == 0;
  };
  // /dev/stdout names whatever standard output is, a regular file too: replacing that file would
  // lose what the command prints there.
  const bool special = under_system(path) || (!ec && under_system(leads_to));
  // A device or descriptor name that leads nowhere (/dev/stdout while standard output is
  // closed) is no file to create.
  if (!exists && special) {
    throw InputError(std::string(option) + ": cannot write " + path +
                     ": it names no open device or descriptor (is standard output closed?)");
  }
  // The command's own standard output or error, by whatever name (/dev/stdout, a link to it, the
  // file it is redirected to): written through that stream, in order with what the command
  // prints there; a second descriptor on the same file would write over it.
  auto same_file = [&](int fd) {
    struct stat of {};
    return fstat(fd, &of) == 0 && of.st_dev == st.st_dev && of.st_ino == st.st_ino;
  };
  if (exists && same_file(STDOUT_FILENO)) {
    shared_ = &std::cout;
  } else if (exists && same_file(STDERR_FILENO)) {
    shared_ = &std::cerr;
  }
  if (shared_) {
    out_.std::ostream::rdbuf(shared_->rdbuf());
  } else if (exists && (special || !S_ISREG(st.st_mode))) {
    out_.open(path, std::ios::binary | std::ios::trunc);  // a device or a pipe: no rename
  } else {
    // A symbolic link keeps pointing where it did: the file it names is replaced (or made).
    if (!ec && !leads_to.empty()) target_ = leads_to;
    const fs::path t(target_);
    // Appended piece by piece: GCC 12 warns (-Wrestrict) of "." + a string, wrongly.
    std::string hidden(1, '.');
    hidden += t.filename().string();
    hidden += ".tmp-XXXXXX";
    std::string name = (t.parent_path() / hidden).string();
    const int fd = mkstemp(name.data());
    if (fd < 0)
      throw InputError(std::string(option) + ": cannot write " + path + ": " +
                       why_not(target_, errno));
    // The file a command leaves gets the mode it had, or the one a new file gets.
    mode_t mode = st.st_mode & 07777;
    if (!exists) {
      const mode_t mask = umask(0);
      umask(mask);
      mode = 0666 & ~mask;
    }
    fchmod(fd, mode);
    close(fd);
    temp_ = name;
    slot_ = remember(temp_);
    install_handler();
    out_.open(temp_, std::ios::binary | std::ios::trunc);
  }
  if (!out_) {
    const int error = errno;
    if (!temp_.empty()) std::remove(temp_.c_str());
    forget(slot_);
    throw InputError(std::string(option) + ": cannot write " + path + ": " + why_not(path, error));
  }
}

OutputFile::~OutputFile() {
  if (committed_ || temp_.empty()) return;
  out_.close();
  std::remove(temp_.c_str());
  forget(slot_);
}

long long OutputFile::written() {
  if (temp_.empty() || finished_) return -1;
  return static_cast<long long>(out_.tellp());
}

bool OutputFile::cut_back(long long at) {
  if (temp_.empty() || finished_ || at < 0) return false;
  out_.flush();
  if (!out_ || truncate(temp_.c_str(), static_cast<off_t>(at)) != 0) return false;
  out_.seekp(static_cast<std::streamoff>(at));
  return static_cast<bool>(out_);
}

void OutputFile::finish() {
  if (finished_) return;
  out_.flush();
  if (!shared_) out_.close();
  if (out_.fail()) throw OutputError("could not finish writing " + path_ + " (is the disk full?)");
  finished_ = true;
}

void OutputFile::rename_into_place() {
  finish();
  if (temp_.empty() || committed_) {
    committed_ = true;
    return;
  }
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
    throw OutputError("could not put " + path_ + " in place: " + std::strerror(errno));
  }
  committed_ = true;
  forget(slot_);
}

std::unique_ptr<OutputFile> open_output(const std::string& path, const char* option) {
  if (path.empty()) return nullptr;
  return std::make_unique<OutputFile>(path, option);
}

void commit_outputs(std::initializer_list<OutputFile*> outputs) {
  for (OutputFile* out : outputs) {
    if (out) out->finish();
  }
  for (OutputFile* out : outputs) {
    if (out) out->rename_into_place();
  }
}

void refuse_clashing_files(const std::vector<NamedFile>& outputs,
                           const std::vector<NamedFile>& inputs) {
  // What a file is: its device and inode when it exists, else its absolute normal path.
  struct Identity {
    bool exists = false;
    dev_t dev{};
    ino_t ino{};
    fs::path path;
    bool operator==(const Identity& o) const {
      return exists == o.exists && (exists ? dev == o.dev && ino == o.ino : path == o.path);
    }
  };
  auto identify = [](const std::string& name) {
    Identity id;
    struct stat st {};
    if (stat(name.c_str(), &st) == 0) {
      id.exists = true;
      id.dev = st.st_dev, id.ino = st.st_ino;
      // A device (/dev/stdout, /dev/null) may take every output: nothing is replaced.
      if (!S_ISREG(st.st_mode)) id.exists = false, id.path = "";
    } else {
      std::error_code ec;
      id.path = fs::weakly_canonical(fs::absolute(name, ec), ec);
      if (ec) id.path = fs::path(name).lexically_normal();
    }
    return id;
  };
  std::vector<std::pair<NamedFile, Identity>> inputs_seen, outputs_seen;
  for (const NamedFile& in : inputs) {
    if (!in.second->empty()) inputs_seen.emplace_back(in, identify(*in.second));
  }
  for (const NamedFile& out : outputs) {
    const auto& [option, path] = out;
    if (path->empty() || *path == "-") continue;
    const Identity id = identify(*path);
    if (!id.exists && id.path.empty()) continue;
    for (const auto& [in, other] : inputs_seen) {
      if (id == other) {
        throw InputError(std::string(option) + " " + *path + " is the input " + in.first + " " +
                         *in.second + ": writing it would replace what the command reads; give " +
                         "the output another name");
      }
    }
    for (const auto& [prev, other] : outputs_seen) {
      if (id == other) {
        // Two spellings of one file (a link, ./, a hard link) are each named, as given.
        const std::string& earlier = *prev.second;
        throw InputError(earlier == *path
                             ? concat({prev.first, " and ", option, " both name ", *path,
                                       ": give each output its own file"})
                             : concat({prev.first, " ", earlier, " and ", option, " ", *path,
                                       " name the same file: give each output its own file"}));
      }
    }
    outputs_seen.emplace_back(out, id);
  }
}

void check_standard_streams() {
  std::cout.flush();
  std::fflush(stderr);
  errno = 0;
  const bool out_ok = std::fflush(stdout) == 0 && !std::ferror(stdout) && !std::cout.fail();
  const int error = errno;
  if (!out_ok) {
    throw OutputError(std::string("cannot write standard output: ") +
                      (error != 0 ? std::strerror(error) : "write failed"));
  }
  if (std::ferror(stderr) || std::cerr.fail()) throw OutputError("cannot write standard error");
}

}  // namespace chainbench
