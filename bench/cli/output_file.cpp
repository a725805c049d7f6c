#include "output_file.h"

#include "input_error.h"

#include <filesystem>
#include <vector>

namespace chainbench {

std::unique_ptr<std::ofstream> open_output(const std::string& path, const char* option) {
  if (path.empty()) return nullptr;
  if (path == "-") {
    throw InputError(std::string(option) +
                     " -: standard output carries the table; give a file name (/dev/stdout works)");
  }
  auto out = std::make_unique<std::ofstream>(path, std::ios::binary | std::ios::trunc);
  if (!*out) throw InputError(std::string(option) + ": cannot write " + path);
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
