#include "output_file.h"

#include "input_error.h"

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

void finish_output(std::ofstream* out, const std::string& path) {
  if (out && !out->flush())
    throw OutputError("could not finish writing " + path + " (is the disk full?)");
}

}  // namespace chainbench
