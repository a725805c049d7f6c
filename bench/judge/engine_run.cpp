// SPDX-License-Identifier: MIT
#include "judge/engine_run.h"

namespace chainbench {

std::optional<double> EngineRun::counter(std::string_view name) const {
  const std::vector<CounterDef>& defs = counter_defs();
  for (std::size_t i = 0; i < defs.size() && i < counters.size(); ++i) {
    if (defs[i].name == name) return counters[i];
  }
  return std::nullopt;
}

std::optional<bool> EngineRun::stable() const {
  if (!metrics.finite) return std::nullopt;
  return *metrics.finite && *metrics.in_bounds && !*metrics.blow_up && !*metrics.tunnelled &&
         degraded_steps == 0;
}

}  // namespace chainbench
