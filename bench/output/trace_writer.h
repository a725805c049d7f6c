// SPDX-License-Identifier: MIT
// The trace CSV of `chainbench run --trace`: every body's state after every step, in one of two
// forms (docs/output-formats.md §4):
//   dense (the default): engine,step,time,body,x,y,vx,vy,angle,displacement,penetration
//     one row per engine, step and body in the world, nothing else: what pandas.read_csv reads
//     as it is. Its metadata (the scene, dt, each engine's full spec, the columns' units) goes to
//     a JSON sidecar (trace_metadata_json, written beside it as FILE.json).
//   sparse: engine,step,body,x,y,vx,vy,angle,displacement,penetration
//     a body's row is written at step 1 and then only when some value in it changed: a missing
//     row repeats the body's previous one, so bodies at rest and static bodies cost one row each,
//     for huge scenes. Comment lines (#) give the format, dt (time is step * dt) and each
//     engine's full spec once. Where bodies come and go (StepView::present), a body has rows only
//     while it is in the world: the first at the state it enters in (step 1 for a body there from
//     the start), and once it has left, one row with its seven values empty, at the first state
//     it is not in.
// The engine goes by its label, the body by its name; numbers are exact (support/number_text.h),
// so nothing is rounded.
#pragma once

#include "model/scene.h"
#include "run/step_observer.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace chainbench {

enum class TraceFormat { kDense, kSparse };

class TraceWriter final : public StepObserver {
 public:
  TraceWriter(std::ostream& out, const Scene& scene, TraceFormat format = TraceFormat::kDense);
  void begin(const EngineSpec& spec, std::span<const CounterDef> counters) override;
  void observe(const StepView& view) override;
  // The engine run last began ran to its end: its rows stay (the sidecar lists it). Nothing when
  // no run began since the last call.
  void finished() {
    if (specs_.size() > finished_.size()) finished_.push_back(specs_.back());
  }
  // The engines whose runs finished, in the order they ran.
  const std::vector<EngineSpec>& finished_engines() const { return finished_; }

 private:
  void observe_dense(const StepView& view);
  TraceFormat format_;
  std::vector<EngineSpec> specs_, finished_;
  using Row = std::array<double, 7>;  // x, y, vx, vy, angle, displacement, penetration
  std::ostream& out_;
  std::vector<std::string> names_;  // quoted where CSV needs it
  std::string label_;
  std::vector<Row> last_;            // per body: its last written row
  std::vector<std::uint8_t> shown_;  // per body: its last row is a state (not none, not a leave)
  std::string line_, prefix_;
};

// Where the dense trace at `trace_path` keeps its metadata: beside it, trace_path + ".json".
std::string trace_metadata_path(const std::string& trace_path);
// Removes the file at `path` if it is a dense trace's metadata (chainbench.trace/1): true if it
// did. Anything else there is left alone.
bool remove_trace_metadata(const std::string& path);
// The dense trace's sidecar (chainbench.trace/1): the scene, dt, the engines that finished with
// their full specs, whether the run was interrupted, and every column with its unit.
nlohmann::ordered_json trace_metadata_json(const Scene& scene,
                                           const std::vector<EngineSpec>& engines,
                                           bool interrupted);

// A CSV field: as is, or quoted (quotes doubled) when it holds a comma, quote or line break.
std::string csv_field(const std::string& text);
// A CSV field always quoted (quotes doubled), for columns whose fields are quoted whatever they
// hold.
std::string csv_quoted(const std::string& text);

}  // namespace chainbench
