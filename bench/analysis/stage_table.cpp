#include "stage_table.h"

#include "text_table.h"

#include <algorithm>
#include <string>
#include <vector>

namespace chainbench {

void print_stage_table(std::ostream& out, const RunReport& report) {
  std::vector<const EngineRun*> runs;
  for (const EngineRun& r : report.runs)
    runs.push_back(&r);
  if (report.reference) runs.push_back(&*report.reference);
  bool any = false;
  for (const EngineRun* r : runs) {
    if (r->stages.empty()) continue;
    if (!any) {
      out << "\nstages (each engine's own timing of its step: mean ms per timed step, and share "
             "of its mean ms/step):\n";
      any = true;
    }
    const double step = r->timing.mean_ms;
    TextTable table({"stage", "ms/step", "share"});
    double staged = 0.0;
    for (const StageMean& s : r->stages) {
      staged += s.ms;
      table.add({s.name, fmt_ms(s.ms), step > 0.0 ? fmt_g(100.0 * s.ms / step, 2) + "%" : "-"});
    }
    const double rest = std::max(0.0, step - staged);
    table.add(
        {"(outside them)", fmt_ms(rest), step > 0.0 ? fmt_g(100.0 * rest / step, 2) + "%" : "-"});
    table.add({"(step)", fmt_ms(step), "100%"});
    out << '\n' << r->spec.label() << ":\n";
    table.print(out);
  }
}

}  // namespace chainbench
