// SPDX-License-Identifier: MIT
#include "support/text_table.h"

#include "support/number_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace chainbench {

namespace {

// `text` in lines of at most `room` characters, broken at spaces; a longer word is cut.
std::vector<std::string> wrapped(const std::string& text, std::size_t room) {
  std::vector<std::string> lines(1);
  std::size_t at = 0;
  while (at < text.size()) {
    if (text[at] == ' ') {
      ++at;
      continue;
    }
    const std::size_t end = std::min(text.find(' ', at), text.size());
    std::string word = text.substr(at, end - at);
    at = end;
    while (!word.empty()) {
      std::string& line = lines.back();
      const std::size_t need = word.size() + (line.empty() ? 0 : 1);
      if (line.size() + need <= room) {
        line += (line.empty() ? "" : " ") + word;
        word.clear();
      } else if (line.empty()) {  // a word longer than the room: as much as fits, then the rest
        line = word.substr(0, room);
        word.erase(0, room);
        lines.emplace_back();
      } else {
        lines.emplace_back();
      }
    }
  }
  if (lines.size() > 1 && lines.back().empty()) lines.pop_back();
  return lines;
}

std::size_t longest_word(const std::string& text) {
  std::size_t longest = 0, at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    longest = std::max(longest, end - at);
    at = end + 1;
  }
  return longest;
}

}  // namespace

void TextTable::print(std::ostream& out) const {
  std::vector<std::size_t> width;
  for (const auto& row : rows_) {
    width.resize(std::max(width.size(), row.size()), 0);
    for (std::size_t c = 0; c < row.size(); ++c)
      width[c] = std::max(width[c], row[c].size());
  }
  const std::size_t n = width.size();
  if (wrap_ > 0 && n > 1) {
    // How narrow each column may become: the first not at all, the last to kMinWrapped (a longer
    // word cut), the others to their longest word.
    std::vector<std::size_t> least(n, 0);
    for (const auto& row : rows_) {
      for (std::size_t c = 1; c < row.size() && c + 1 < n; ++c)
        least[c] = std::max(least[c], longest_word(row[c]));
    }
    least[0] = width[0];
    least[n - 1] = std::min(width[n - 1], kMinWrapped);
    std::size_t total = 2 * (n - 1);
    for (const std::size_t w : width)
      total += w;
    // The last column (help) gives first, then the widest of the others that can (the later of
    // equals), a character at a time, until the table fits or none can.
    while (total > wrap_) {
      std::size_t giver = 0;
      for (std::size_t c = 1; c + 1 < n; ++c) {
        if (width[c] > least[c] && (giver == 0 || width[c] >= width[giver])) giver = c;
      }
      if (width[n - 1] > least[n - 1]) giver = n - 1;
      if (giver == 0) break;
      --width[giver];
      --total;
    }
  }
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    // Each cell in lines of its column's width (one line unless the table wraps).
    std::vector<std::vector<std::string>> cells;
    std::size_t height = 1;
    for (std::size_t c = 0; c < rows_[r].size(); ++c) {
      cells.push_back(wrap_ > 0 && c > 0 ? wrapped(rows_[r][c], width[c])
                                         : std::vector<std::string>{rows_[r][c]});
      height = std::max(height, cells.back().size());
    }
    for (std::size_t k = 0; k < height; ++k) {
      std::string line;
      for (std::size_t c = 0; c < cells.size(); ++c) {
        const std::string cell = k < cells[c].size() ? cells[c][k] : std::string();
        const std::string pad(width[c] - std::min(width[c], cell.size()), ' ');
        // Text left-aligned; in a table of numbers the first column (names) only.
        if (c == 0) {
          line += cell + pad;
        } else {
          line += wrap_ > 0 ? "  " + cell + pad : "  " + pad + cell;
        }
      }
      while (!line.empty() && line.back() == ' ')
        line.pop_back();
      out << line << '\n';
    }
    if (r == 0) {
      std::size_t total = 0;
      for (std::size_t c = 0; c < n; ++c)
        total += width[c] + (c ? 2 : 0);
      out << std::string(total, '-') << '\n';
    }
  }
}

std::string concat(std::initializer_list<std::string_view> parts) {
  std::size_t size = 0;
  for (const std::string_view p : parts)
    size += p.size();
  std::string s;
  s.reserve(size);
  for (const std::string_view p : parts)
    s.append(p);
  return s;
}

std::string fmt_g(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

int digits_apart(double a, double b, int at_least) {
  if (a == b) return at_least;
  int digits = at_least;
  while (digits < 17 && fmt_g(a, digits) == fmt_g(b, digits))
    ++digits;
  return digits;
}

std::string fmt_limit(double limit, int digits) {
  return digits <= 3 ? fmt_g(limit) : exact_number(limit);
}

std::string fmt_ms(double ms) {
  char buf[32];
  std::snprintf(buf, sizeof buf, ms >= 100 ? "%.0f" : (ms >= 1 ? "%.2f" : "%.4f"), ms);
  return buf;
}

}  // namespace chainbench
