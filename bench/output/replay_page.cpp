// SPDX-License-Identifier: MIT
#include "output/replay_page.h"

#include "replay/replay_assets.h"
#include "support/input_error.h"
#include "support/text_table.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace chainbench {
namespace {

using nlohmann::ordered_json;

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* const digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t{bytes[i]} << 16) |
                            (i + 1 < bytes.size() ? std::uint32_t{bytes[i + 1]} << 8 : 0u) |
                            (i + 2 < bytes.size() ? std::uint32_t{bytes[i + 2]} : 0u);
    out += digits[(n >> 18) & 63];
    out += digits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

std::size_t base64_size(std::size_t bytes) {
  return (bytes + 2) / 3 * 4;
}

std::string html_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

ordered_json numbers(const std::vector<double>& values) {
  ordered_json a = ordered_json::array();
  for (const double v : values)
    a.push_back(json_number(v));
  return a;
}

ordered_json scene_json(const Scene& s) {
  ordered_json names = ordered_json::array(), kinds = ordered_json::array();
  ordered_json half = ordered_json::array(), centers = ordered_json::array();
  for (const SceneBody& b : s.bodies) {
    names.push_back(b.name);
    kinds.push_back(to_string(b.kind));
    half.push_back(b.half_extents.x);
    half.push_back(b.half_extents.y);
    centers.push_back(b.center.x);
    centers.push_back(b.center.y);
  }
  ordered_json expect = ordered_json::array();
  for (const Expectation& e : s.expect)
    expect.push_back(expectation_json(s, e));
  ordered_json j = {{"name", s.name},
                    {"description", s.description},
                    {"steps", s.steps},
                    {"dt", s.dt},
                    {"bodies", s.bodies.size()},
                    {"names", std::move(names)},
                    {"kinds", std::move(kinds)},
                    {"half_extents", std::move(half)},
                    {"centers", std::move(centers)},
                    {"expect", std::move(expect)}};
  if (s.penetration_tolerance) j["penetration_tolerance"] = *s.penetration_tolerance;
  if (s.has_lifetimes()) {  // the states each body is in (to: null for the last)
    ordered_json from = ordered_json::array(), to = ordered_json::array();
    for (const SceneBody& b : s.bodies) {
      from.push_back(b.from_step);
      to.push_back(b.to_step < s.steps ? ordered_json(b.to_step) : ordered_json(nullptr));
    }
    j["lives"] = {{"from", std::move(from)}, {"to", std::move(to)}};
  }
  return j;
}

ordered_json verdict_json(const Verdict& v) {
  ordered_json findings = ordered_json::array();
  for (const Finding& f : v.findings) {
    ordered_json j = {{"class", to_string(f.what)}, {"detail", f.detail}, {"step", f.step}};
    j["bodies"] = ordered_json::array();
    for (std::size_t k = 0; k < f.bodies.size() && k < 100; ++k)
      j["bodies"].push_back(f.bodies[k]);
    if (f.position) j["at"] = {json_number(f.position->x), json_number(f.position->y)};
    findings.push_back(std::move(j));
  }
  return {{"class", to_string(v.worst)}, {"findings", std::move(findings)}};
}

// An engine's entry, all but its positions (filled in once the stride is chosen).
ordered_json engine_json(const Scene& s, const EngineRun& run, const ReplayTrack& t) {
  ordered_json e;
  e["label"] = run.spec.label();
  e["spec"] = run.engine;
  e["ms_per_step"] = run.timing.median_ms;
  e["verdict"] = run.verdict ? verdict_json(*run.verdict) : ordered_json(nullptr);
  e["expect"] = run.expect ? ordered_json{{"pass", run.expect->pass},
                                          {"max_error", json_number(run.expect->max_error)}}
                           : ordered_json(nullptr);
  e["interrupted"] = run.interrupted;
  e["positions"] = "";
  // The exact final centres of the bodies that left their initial one.
  ordered_json bodies = ordered_json::array(), xy = ordered_json::array();
  for (std::size_t i = 0; i < s.bodies.size() && i < run.final_positions.size(); ++i) {
    const Vec2d p = run.final_positions[i], c = s.bodies[i].center;
    if (std::memcmp(&p, &c, sizeof p) == 0 || !run.present_at_end(s, i)) continue;
    bodies.push_back(i);
    xy.push_back(json_number(p.x));
    xy.push_back(json_number(p.y));
  }
  e["final"] = {{"bodies", std::move(bodies)}, {"xy", std::move(xy)}};
  ordered_json series = {
      {"efd", numbers(t.efd)}, {"penetration", numbers(t.penetration)}, {"ms", numbers(t.ms)}};
  if (!t.error_max.empty()) {
    series["error_max"] = numbers(t.error_max);
    series["error_rms"] = numbers(t.error_rms);
  }
  e["series"] = std::move(series);
  ordered_json kinds = ordered_json::array(), steps = ordered_json::array();
  ordered_json kind = ordered_json::array(), body = ordered_json::array();
  std::vector<std::string> seen;
  for (const ReplayTrack::Event& ev : t.events) {
    auto at = std::find(seen.begin(), seen.end(), ev.kind);
    if (at == seen.end()) at = seen.insert(seen.end(), ev.kind), kinds.push_back(ev.kind);
    steps.push_back(ev.step);
    kind.push_back(at - seen.begin());
    body.push_back(ev.body);
  }
  e["events"] = {{"kinds", std::move(kinds)},
                 {"step", std::move(steps)},
                 {"kind", std::move(kind)},
                 {"body", std::move(body)},
                 {"left_out", t.events_left_out}};
  e["counted"] = ordered_json::array();
  for (const ReplayTrack::Counted& c : t.counted) {
    ordered_json at = ordered_json::array(), value = ordered_json::array();
    for (const auto& [step, v] : c.steps)
      at.push_back(step), value.push_back(json_number(v));
    e["counted"].push_back(
        {{"name", c.name}, {"help", c.help}, {"step", std::move(at)}, {"value", std::move(value)}});
  }
  e["degraded"] = t.degraded;
  return e;
}

// JSON inside a <script> element, with no <, > or & at all: "</script" would end it early, and
// "<!--" followed by "<script" puts the HTML tokenizer in a state where the element's own end tag
// no longer ends it (the page goes blank). JSON has these only inside strings, where \u003c and
// the like mean the same characters.
std::string script_safe(const ordered_json& j) {
  const std::string text = j.dump(-1, ' ', true);
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '>') {
      out += "\\u003e";
    } else if (c == '&') {
      out += "\\u0026";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

void check_replay_size(const Scene& scene) {
  const double body_states =
      static_cast<double>(scene.bodies.size()) * (static_cast<double>(scene.steps) + 1.0);
  if (body_states > kMaxReplayBodyStates) {
    throw InputError(concat(
        {"replay: scene ", scene.name, " has ", std::to_string(scene.bodies.size()),
         " bodies over ", std::to_string(scene.steps), " steps, more than a page holds (",
         fmt_g(kMaxReplayBodyStates, 3), " body-steps); give fewer --steps or a smaller scene"}));
  }
}

ReplayPageSummary write_replay_page(std::ostream& out, const RunReport& report,
                                    const ReplayRecorder& recorder,
                                    const ReplayPageOptions& options) {
  const Scene& s = *report.scene;
  std::vector<const EngineRun*> runs;
  for (const EngineRun& r : report.runs)
    runs.push_back(&r);
  if (report.reference) runs.push_back(&*report.reference);
  ordered_json data;
  data["schema"] = "chainbench.replay/1";
  data["generator"] = options.generator;
  data["scene"] = scene_json(s);
  data["quantum"] = recorder.quantum();
  data["stride"] = 1;
  data["reference"] = nullptr;
  // Ctrl-C: the page shows the engines that finished before it, and says so.
  data["interrupted"] = report.interrupted;
  data["engines"] = ordered_json::array();
  std::vector<const ReplayTrack*> tracks;
  for (const EngineRun* run : runs) {
    const auto t = std::find_if(recorder.tracks().begin(), recorder.tracks().end(),
                                [&](const ReplayTrack& x) { return x.spec == run->spec; });
    if (t == recorder.tracks().end()) continue;  // not recorded: not shown
    if (recorder.reference() && run->spec == *recorder.reference())
      data["reference"] = tracks.size();
    tracks.push_back(&*t);
    data["engines"].push_back(engine_json(s, *run, *t));
  }
  const std::string page = replay_assets::page();
  const std::string style = replay_assets::style();
  const std::string script = replay_assets::script();
  const std::size_t fixed =
      page.size() + style.size() + script.size() + script_safe(data).size() + 2 * s.name.size();

  // The fewest steps left out that fit the page in its limit.
  auto positions_size = [&](int stride) {
    std::size_t total = 0;
    for (const ReplayTrack* t : tracks)
      total += base64_size(stride == 1 ? t->positions.bytes().size()
                                       : t->positions.decimated(stride).size());
    return total;
  };
  int stride = 1;
  std::size_t size = positions_size(1);
  const std::size_t room = options.max_bytes > fixed ? options.max_bytes - fixed : 1;
  while (size > room && stride < s.steps) {
    const double ratio = static_cast<double>(size) / static_cast<double>(room);
    stride = std::min(s.steps, std::max(stride + 1, static_cast<int>(std::ceil(stride * ratio))));
    size = positions_size(stride);
  }
  if (fixed + size > options.max_bytes) {
    throw InputError("the replay page of " + s.name + " needs at least " +
                     fmt_g(static_cast<double>(fixed + size) / 1e6, 3) +
                     " MB (its player, and the first and last state of every body), more than " +
                     options.limit_option + " " +
                     fmt_g(static_cast<double>(options.max_bytes) / 1e6, 3) +
                     " allows: raise it, or write fewer engines or steps");
  }
  data["stride"] = stride;
  for (std::size_t k = 0; k < tracks.size(); ++k)
    data["engines"][k]["positions"] = base64(tracks[k]->positions.decimated(stride));

  const std::string title = "chainbench replay: " + s.name;
  const std::pair<const char*, std::string> slots[] = {
      {"{{GENERATOR}}", html_escape(options.generator)},
      {"{{TITLE}}", html_escape(title)},
      {"{{STYLE}}", style},
      {"{{DATA}}", script_safe(data)},
      {"{{SCRIPT}}", script}};
  // Each slot filled once, in the order the template has them, so that text in the data that
  // looks like a slot stays text.
  std::size_t at = 0, written = 0;
  for (const auto& [slot, text] : slots) {
    const std::size_t found = page.find(slot, at);
    if (found == std::string::npos) throw std::logic_error(std::string("page.html lacks ") + slot);
    out.write(page.data() + at, static_cast<std::streamsize>(found - at));
    out << text;
    written += found - at + text.size();
    at = found + std::strlen(slot);
  }
  out.write(page.data() + at, static_cast<std::streamsize>(page.size() - at));
  written += page.size() - at;
  return {written, stride, recorder.quantum()};
}

}  // namespace chainbench
