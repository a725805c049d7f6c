// SPDX-License-Identifier: MIT
#include "output/trace_writer.h"
#include "support/number_text.h"

#include <cstdio>
#include <cstring>
#include <fstream>

namespace chainbench {

std::string csv_quoted(const std::string& text) {
  std::string q = "\"";
  for (const char c : text) {
    if (c == '"') q.push_back('"');
    q.push_back(c);
  }
  q.push_back('"');
  return q;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos && !text.empty()) return text;
  return csv_quoted(text);
}

namespace {

bool same_bits(const std::array<double, 7>& a, const std::array<double, 7>& b) {
  return std::memcmp(a.data(), b.data(), sizeof a) == 0;
}

// The dense form's columns and their units, in order.
constexpr std::array<std::pair<const char*, const char*>, 11> kDenseColumns = {{
    {"engine", "the engine's label (the sidecar gives its full spec)"},
    {"step", "steps taken: 1 after the first"},
    {"time", "s: step * dt"},
    {"body", "the body's name"},
    {"x", "m: centre"},
    {"y", "m: centre"},
    {"vx", "m/s"},
    {"vy", "m/s"},
    {"angle", "rad"},
    {"displacement", "m: the body's energy-free displacement in this step"},
    {"penetration", "m: the body's deepest overlap after this step"},
}};

}  // namespace

std::string trace_metadata_path(const std::string& trace_path) {
  return trace_path + ".json";
}

bool remove_trace_metadata(const std::string& path) {
  std::ifstream in(path);
  if (!in) return false;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("schema", "") != "chainbench.trace/1")
    return false;
  in.close();
  return std::remove(path.c_str()) == 0;
}

nlohmann::ordered_json trace_metadata_json(const Scene& scene,
                                           const std::vector<EngineSpec>& engines,
                                           bool interrupted) {
  nlohmann::ordered_json j;
  j["schema"] = "chainbench.trace/1";
  j["format"] = "dense";
  j["scene"] = {{"name", scene.name},
                {"bodies", scene.bodies.size()},
                {"steps", scene.steps},
                {"dt", scene.dt}};
  j["rows"] = scene.has_lifetimes() ? "one per engine, step and body in the world at that step"
                                    : "one per engine, step and body";
  j["engines"] = nlohmann::ordered_json::array();
  for (const EngineSpec& spec : engines)
    j["engines"].push_back({{"label", spec.label()}, {"spec", spec.str()}});
  j["interrupted"] = interrupted;
  j["columns"] = nlohmann::ordered_json::array();
  for (const auto& [name, meaning] : kDenseColumns)
    j["columns"].push_back({{"name", name}, {"meaning", meaning}});
  return j;
}

TraceWriter::TraceWriter(std::ostream& out, const Scene& scene, TraceFormat format)
    : format_(format), out_(out) {
  for (const SceneBody& b : scene.bodies)
    names_.push_back(csv_field(b.name));
  line_.reserve(256);
  if (format_ == TraceFormat::kDense) {
    for (std::size_t c = 0; c < kDenseColumns.size(); ++c)
      out_ << (c ? "," : "") << kDenseColumns[c].first;
    out_ << '\n';
    return;
  }
  out_ << "engine,step,body,x,y,vx,vy,angle,displacement,penetration\n"
       << "# chainbench trace 2: a body's row is written at step 1 and then when a value in it "
          "changes; a missing row repeats the body's previous row\n";
  append_exact_number(line_, scene.dt);
  out_ << "# dt " << line_ << " s (time = step * dt)\n"
       << "# steps " << scene.steps << " (rows after an engine's last row repeat it)\n";
  if (scene.has_lifetimes()) {
    out_ << "# bodies come and go: a body has rows only while it is in the world, the first at the "
            "state it enters in; a row with its values empty says it left in the step before\n";
  }
}

void TraceWriter::begin(const EngineSpec& spec, std::span<const CounterDef>) {
  specs_.push_back(spec);
  label_ = csv_field(spec.label());
  if (format_ == TraceFormat::kSparse)
    out_ << "# engine " << spec.label() << " = " << spec.str() << '\n';
  last_.assign(names_.size(), Row{});
  shown_.assign(names_.size(), 0);
}

void TraceWriter::observe_dense(const StepView& v) {
  const BodyState& s = *v.state;
  // engine,step,time, once a step (buffers kept from step to step: no allocation per row)
  prefix_ = label_;
  prefix_ += ',';
  prefix_ += std::to_string(v.step);
  prefix_ += ',';
  append_exact_number(prefix_, v.time);
  prefix_ += ',';
  for (std::size_t i = 0; i < s.position.size(); ++i) {
    if (!v.present.empty() && !v.present[i]) continue;  // out of the world: no state, no row
    line_ = prefix_;
    line_ += names_[i];
    for (const double value : {s.position[i].x, s.position[i].y, s.velocity[i].x, s.velocity[i].y,
                               s.angle[i], v.displacement[i], v.penetration[i]}) {
      line_ += ',';
      append_exact_number(line_, value);
    }
    line_ += '\n';
    out_ << line_;
  }
}

void TraceWriter::observe(const StepView& v) {
  if (format_ == TraceFormat::kDense) {
    observe_dense(v);
    return;
  }
  const BodyState& s = *v.state;
  auto start = [&](std::size_t i) {
    line_ = label_;
    line_ += ',';
    line_ += std::to_string(v.step);
    line_ += ',';
    line_ += names_[i];
  };
  for (std::size_t i = 0; i < s.position.size(); ++i) {
    if (!v.present.empty() && !v.present[i]) {  // out of the world: its entries are no state
      if (!shown_[i]) continue;
      shown_[i] = 0;
      start(i);
      line_ += ",,,,,,,\n";  // it left in the step before this state
      out_ << line_;
      continue;
    }
    const Row row = {s.position[i].x, s.position[i].y,   s.velocity[i].x, s.velocity[i].y,
                     s.angle[i],      v.displacement[i], v.penetration[i]};
    if (shown_[i] && same_bits(row, last_[i])) continue;
    last_[i] = row;
    shown_[i] = 1;
    start(i);
    for (const double value : row) {
      line_ += ',';
      append_exact_number(line_, value);
    }
    line_ += '\n';
    out_ << line_;
  }
}

}  // namespace chainbench
