// SPDX-License-Identifier: MIT
#include "judge/metric_table.h"

#include "support/text_table.h"

#include <cmath>
#include <string_view>

namespace chainbench {
namespace {

using nlohmann::ordered_json;

std::optional<double> flag(const std::optional<bool>& b) {
  return b ? std::optional<double>(*b ? 1.0 : 0.0) : std::nullopt;
}

ordered_json number(double v) {
  return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr);  // JSON has no NaN
}

void worst_overlap(ordered_json& m, const Metrics& mt, const Scene& s) {
  if (!mt.worst_overlap) {
    m["worst_overlap"] = nullptr;  // measured: nothing overlapped
    return;
  }
  const PairOverlap& w = *mt.worst_overlap;
  m["worst_overlap"] = {{"bodies", {s.bodies[w.a].name, s.bodies[w.b].name}},
                        {"depth", number(w.depth)},
                        {"tolerance", number(w.tolerance)},
                        {"step", w.step}};
}

void peak_where(ordered_json& m, const Metrics& mt, const Scene& s) {
  m["peak_speed_body"] = s.bodies[mt.peak_speed_body].name;
  m["peak_speed_step"] = mt.peak_speed_step;
}

void unbounded_why(ordered_json& m, const Metrics& mt, const Scene&) {
  if (!mt.speed_unbounded.empty()) m["speed_unbounded"] = mt.speed_unbounded;
}

void escaped_names(ordered_json& m, const Metrics& mt, const Scene& s) {
  m["escaped"] = ordered_json::array();
  for (const std::size_t b : mt.escaped)
    m["escaped"].push_back(s.bodies[b].name);
}

void first_tunnel(ordered_json& m, const Metrics& mt, const Scene& s) {
  if (!mt.tunnel) return;
  m["tunnelling"] = {{"body", s.bodies[mt.tunnel->body].name},
                     {"through", s.bodies[mt.tunnel->through].name},
                     {"step", mt.tunnel->step},
                     {"count", mt.tunnel_count}};
}

// The rows, in the order the run JSON writes them.
const MetricDef kMetrics[] = {
    {"efd_total", MetricGroup::kDisplacement, MetricKind::kNumber, "m", "sum over body-steps",
     "lower is better; 0 for bodies that move as their velocities say",
     "energy-free displacement: with h = dt, d = ‖x(n+1) − x(n) − h·v(n+1)‖ per body and step",
     "energy_free_displacement", "total", "", "", kRunCsv,
     [](const Metrics& m) { return m.efd_total; }},
    {"efd_per_body_step", MetricGroup::kDisplacement, MetricKind::kNumber, "m",
     "mean over body-steps", "lower is better", "energy-free displacement, per body and step",
     "energy_free_displacement", "per_body_step", "EFD/body-step m", "energy_free_displacement",
     kRunCsv | kRunTable | kSweep, [](const Metrics& m) { return m.efd_per_body_step; }},
    {"efd_max_step", MetricGroup::kDisplacement, MetricKind::kNumber, "m",
     "largest of any body-step", "lower is better",
     "energy-free displacement of the worst body and step", "energy_free_displacement", "max_step",
     "", "", kRunCsv, [](const Metrics& m) { return m.efd_max_step; }},
    {"max_penetration", MetricGroup::kPenetration, MetricKind::kNumber, "m",
     "largest after any step", "lower is better; each pair is judged against its tolerance",
     "deepest overlap of any pair (at least one dynamic), along the axis of least penetration", "",
     "max_penetration", "max pen m", "max_penetration",
     kRunCsv | kRunTable | kSweep | kStressJson | kStressTable,
     [](const Metrics& m) { return m.max_penetration; }, worst_overlap, "`worst_overlap`",
     "the overlap deepest relative to its tolerance: `bodies` [name, name], `depth` m, "
     "`tolerance` m, `step`; `null` when nothing overlapped"},
    {"peak_speed", MetricGroup::kStability, MetricKind::kNumber, "m/s", "largest of any body-step",
     "at most `speed_bound`", "fastest displacement of a body in one step / dt, from positions", "",
     "peak_speed", "peak m/s", "", kRunCsv | kRunTable | kStressJson | kStressTable,
     [](const Metrics& m) { return m.peak_speed; }, peak_where,
     "`peak_speed_body`, `peak_speed_step`",
     "where it happened (the first body and step 0 when nothing moved)"},
    {"speed_bound", MetricGroup::kStability, MetricKind::kNumber, "m/s",
     "the scene's: the largest of its bodies' bounds", "a bound, not a score",
     "the largest per-body speed the scene allows; null when the scene bounds none", "",
     "speed_bound", "", "", kStressJson, [](const Metrics& m) { return m.speed_bound; },
     unbounded_why, "`speed_unbounded`", "why no bound exists; present only then"},
    {"finite", MetricGroup::kStability, MetricKind::kFlag, "", "every body-step", "true is right",
     "every position and velocity stayed finite", "", "finite", "", "", kRunCsv | kStressJson,
     [](const Metrics& m) { return flag(m.finite); }},
    {"in_bounds", MetricGroup::kStability, MetricKind::kFlag, "", "every body at the end",
     "true is right", "no body ended farther from its start than the scene can send it", "",
     "in_bounds", "", "", kRunCsv | kStressJson, [](const Metrics& m) { return flag(m.in_bounds); },
     escaped_names, "`escaped`",
     "the names of the bodies that ended out of bounds (the CSV: how many)"},
    {"blow_up", MetricGroup::kStability, MetricKind::kFlag, "",
     "any body over any stretch of steps", "false is right",
     "some body travelled, over some stretch of steps, more than its speed bound allows", "",
     "blow_up", "", "", kStressJson, [](const Metrics& m) { return flag(m.blow_up); }},
    {"tunnelled", MetricGroup::kStability, MetricKind::kFlag, "", "any pair over any step",
     "false is right", "a body passed through another", "", "tunnelled", "", "",
     kRunCsvLate | kStressJson, [](const Metrics& m) { return flag(m.tunnelled); }, first_tunnel,
     "`tunnelling`",
     "{`body`, `through`, `step`, `count`}: the first case, and how many; present only when true"},
    {"escaped", MetricGroup::kStability, MetricKind::kCount, "", "bodies at the end", "0 is right",
     "bodies that ended farther from their start than the scene can send them", "", "", "", "",
     kRunCsvLate,
     [](const Metrics& m) {
       return m.in_bounds ? std::optional<double>(static_cast<double>(m.escaped.size()))
                          : std::nullopt;
     }},
};

}  // namespace

const char* to_string(MetricGroup group) {
  switch (group) {
    case MetricGroup::kDisplacement:
      return "displacement";
    case MetricGroup::kPenetration:
      return "penetration";
    case MetricGroup::kStability:
      return "stability";
  }
  return "?";
}

bool measured(const Metrics& m, MetricGroup group) {
  switch (group) {
    case MetricGroup::kDisplacement:
      return m.efd_total.has_value();
    case MetricGroup::kPenetration:
      return m.max_penetration.has_value();
    case MetricGroup::kStability:
      return m.peak_speed.has_value();
  }
  return false;
}

static_assert(std::size(kMetrics) <= kMaxMetrics, "a stress child's record holds kMaxMetrics");

std::span<const MetricDef> metric_table() {
  return kMetrics;
}

const MetricDef* find_metric(const std::string& name) {
  for (const MetricDef& def : kMetrics) {
    if (name == def.name) return &def;
  }
  return nullptr;
}

std::string metric_cell(const MetricDef& def, const std::optional<double>& value) {
  if (!value) return "-";
  switch (def.kind) {
    case MetricKind::kFlag:
      return *value != 0.0 ? "yes" : "NO";
    case MetricKind::kCount:
      return std::to_string(static_cast<long long>(*value));
    case MetricKind::kNumber:
      break;
  }
  return fmt_g(*value);
}

std::string metric_csv(const MetricDef& def, const std::optional<double>& value) {
  if (!value) return "";
  switch (def.kind) {
    case MetricKind::kFlag:
      return *value != 0.0 ? "1" : "0";
    case MetricKind::kCount:
      return std::to_string(static_cast<long long>(*value));
    case MetricKind::kNumber:
      break;
  }
  return fmt_g(*value, 9);
}

std::string metric_docs_table() {
  std::string out =
      "| key | run CSV | group | unit | over the run | read | meaning |\n"
      "|---|---|---|---|---|---|---|\n";
  for (const MetricDef& def : kMetrics) {
    const std::string_view block = def.json_block;
    const std::string key = *def.json_key == '\0' ? std::string("-")
                            : block.empty()       ? concat({"`", def.json_key, "`"})
                                                  : concat({"`", block, ".", def.json_key, "`"});
    const std::string unit =
        *def.unit ? def.unit : (def.kind == MetricKind::kFlag ? "flag" : "count");
    const std::string csv =
        def.outputs & (kRunCsv | kRunCsvLate) ? concat({"`", def.name, "`"}) : std::string("-");
    out += concat({"| ", key, " | ", csv, " | ", to_string(def.group), " | ", unit, " | ",
                   def.aggregate, " | ", def.reading, " | ", def.help, " |\n"});
    if (def.details) {
      out += concat({"| ", def.details_keys, " | - | ", to_string(def.group), " | | | | ",
                     def.details_help, " |\n"});
    }
  }
  return out;
}

}  // namespace chainbench
