// SPDX-License-Identifier: MIT
// The trace CSV of `chainbench run --trace`: every body's state after every step, in a form that
// stays small for big scenes (README.md, "The trace CSV"):
//   engine,step,body,x,y,vx,vy,angle,displacement,penetration
// The engine by its label, the body by its name; comment lines (#) give the format, dt (time is
// step * dt) and each engine's full spec once. A body's row is written at step 1 and then only
// when some value in it changed: a missing row repeats the body's previous one, so bodies at rest
// and static bodies cost one row each. Numbers are exact (support/number_text.h), so nothing is
// rounded. Where bodies come and go (StepView::present), a body has rows
// only while it is in the world: the first at the state it enters in (step 1 for a body there
// from the start), and once it has left, one row with its seven values empty, at the first state
// it is not in.
#pragma once

#include "model/scene.h"
#include "run/step_observer.h"

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace chainbench {

class TraceWriter final : public StepObserver {
 public:
  TraceWriter(std::ostream& out, const Scene& scene);
  void begin(const EngineSpec& spec, std::span<const CounterDef> counters) override;
  void observe(const StepView& view) override;

 private:
  using Row = std::array<double, 7>;  // x, y, vx, vy, angle, displacement, penetration
  std::ostream& out_;
  std::vector<std::string> names_;  // quoted where CSV needs it
  std::string label_;
  std::vector<Row> last_;            // per body: its last written row
  std::vector<std::uint8_t> shown_;  // per body: its last row is a state (not none, not a leave)
  std::string line_;
};

// A CSV field: as is, or quoted (quotes doubled) when it holds a comma, quote or line break.
std::string csv_field(const std::string& text);
// A CSV field always quoted (quotes doubled), for columns whose fields are quoted whatever they
// hold.
std::string csv_quoted(const std::string& text);

}  // namespace chainbench
