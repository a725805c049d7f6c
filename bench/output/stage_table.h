// SPDX-License-Identifier: MIT
// `chainbench run --profile`: each engine's step split into the stages the engine itself times
// (Engine::stages), beside the harness's timing of the same steps.
#pragma once

#include "output/report.h"

#include <ostream>

namespace chainbench {

// One row per engine that measured stages: mean ms per timed step of each stage, its share of
// the engine's mean timed step, and what lies outside its stages (drives, bodies added and
// removed, the engine's own bookkeeping); then the engines that time no stages of their own.
void print_stage_table(std::ostream& out, const RunReport& report);

}  // namespace chainbench
