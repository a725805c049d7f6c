// A plain-text table with aligned columns, for terminal reports.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace chainbench {

class TextTable {
 public:
  explicit TextTable(std::vector<std::string> header) : rows_{std::move(header)} {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  void print(std::ostream& out) const;

 private:
  std::vector<std::vector<std::string>> rows_;
};

// Short renderings for tables: "0.0123", "1.2e-07", "-" for missing.
std::string fmt_g(double v, int digits = 3);
std::string fmt_ms(double ms);

}  // namespace chainbench
