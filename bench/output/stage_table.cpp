// SPDX-License-Identifier: MIT
#include "output/stage_table.h"

#include "support/text_table.h"

#include <algorithm>
#include <string>
#include <vector>

namespace chainbench {

void print_stage_table(std::ostream& out, const RunReport& report) {
  std::vector<const EngineRun*> runs;
  for (const EngineRun& r : report.runs)
    runs.push_back(&r);
  if (report.reference) runs.push_back(&*report.reference);
  out << "\nstages (each engine's own timing of its step: mean ms per timed step, and share of "
         "its mean ms/step; the table above gives the median):\n";
  std::string untimed;
  for (const EngineRun* r : runs) {
    if (r->stages.empty()) {
      untimed += (untimed.empty() ? "" : ", ") + r->spec.label();
      continue;
    }
    const double step = r->timing.mean_ms;
    auto share = [&](double ms) { return step > 0.0 ? fmt_g(100.0 * ms / step, 2) + "%" : "-"; };
    TextTable table({"stage", "ms/step", "share"});
    double staged = 0.0;
    for (const StageMean& s : r->stages) {
      staged += s.ms;
      table.add({s.name, fmt_g(s.ms), share(s.ms)});
    }
    const double rest = std::max(0.0, step - staged);
    table.add({"(outside them)", fmt_g(rest), share(rest)});
    table.add({"(step, mean)", fmt_g(step), "100%"});
    out << '\n' << r->spec.label() << ":\n";
    table.print(out);
  }
  if (!untimed.empty())
    out << "\nno stage timing of their own: " << untimed
        << " (chain, box2d and box2d3 time their stages)\n";
}

}  // namespace chainbench
