#include "output_file.h"

#include "input_error.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

namespace chainbench {

std::unique_ptr<std::ofstream> open_output(const std::string& path, const char* option) {
  if (path.empty()) return nullptr;
  if (path == "-") {
    throw InputError(std::string(option) +
                     " -: standard output carries the table; give a file name (/dev/stdout works)");
  }
  errno = 0;
  auto out = std::make_unique<std::ofstream>(path, std::ios::binary | std::ios::trunc);
  if (!*out) {
    const int error = errno;
    // Say why: the folder that is not there, a folder where a file should be, or the system's
    // reason.
    std::error_code ec;
    const std::filesystem::path p(path);
    std::string why;
    if (std::filesystem::is_directory(p, ec)) {
      why = "is a directory";
    } else if (const std::filesystem::path dir = p.parent_path();
               !dir.empty() && !std::filesystem::is_directory(dir, ec)) {
      why = "no such directory " + dir.string();
    } else {
      why = error != 0 ? std::strerror(error) : "cannot be opened";
    }
    throw InputError(std::string(option) + ": cannot write " + path + ": " + why);
  }
  return out;
}

void refuse_shared_outputs(
    std::initializer_list<std::pair<const char*, const std::string*>> outputs) {
  std::vector<std::pair<const char*, std::filesystem::path>> seen;
  for (const auto& [option, path] : outputs) {
    if (path->empty() || *path == "-") continue;
    std::error_code ec;
    std::filesystem::path p = std::filesystem::absolute(*path, ec).lexically_normal();
    if (ec) p = *path;
    for (const auto& [other, q] : seen) {
      if (p == q) {
        throw InputError(std::string(other) + " and " + option + " both name " + *path +
                         ": give each output its own file");
      }
    }
    seen.emplace_back(option, std::move(p));
  }
}

void finish_output(std::ofstream* out, const std::string& path) {
  if (out && !out->flush())
    throw OutputError("could not finish writing " + path + " (is the disk full?)");
}

}  // namespace chainbench
