// SPDX-License-Identifier: MIT
// chainbench list, chainbench engines: what can be run, and with which keys.
#include "cli/commands.h"
#include "engines/engine_spec.h"
#include "engines/registry.h"
#include "judge/metric_table.h"
#include "scenes/scene_library.h"
#include "support/number_text.h"
#include "support/text_table.h"

#include <filesystem>
#include <iostream>
#include <memory>

namespace chainbench {
namespace {

// The listings' tables fit a terminal this wide: help text wraps in its own column.
constexpr std::size_t kListWidth = 100;

std::string range(const SceneParam& p) {
  std::string out = "[";  // appended: "[" + a temporary makes GCC 12 warn of a false overlap
  out += exact_number(p.min) + ", " + exact_number(p.max) + "]";
  return p.integer ? out + " whole" : out;
}

int list_scenes() {
  std::cout << "Built-in scenes (chainbench run --scene NAME --set KEY=VALUE ...)\n";
  std::string family;
  for (const SceneRecipe& r : scene_library()) {
    if (r.family != family) {
      family = r.family;
      std::cout << "\n" << family << ":\n";
    }
    std::cout << "  " << r.name << ": " << r.description << "\n";
    // Every key --set takes: the scene's own, then those every scene takes (all_params).
    TextTable t({"    key", "default", "range", "meaning"});
    for (const SceneParam& p : all_params(r))
      t.add({"    " + p.key, exact_number(p.value), range(p), p.help});
    t.wrap_text(kListWidth);
    t.print(std::cout);
  }
  return 0;
}

std::string capabilities(const EngineSpec& spec) {
  const Capabilities c = engine_def(spec.engine).capabilities(spec);
  std::string s;
  auto add = [&](bool has, const char* what) {
    if (has) s += (s.empty() ? "" : ", ") + std::string(what);
  };
  add(c.rotation, "rotation");
  add(c.friction, "friction");
  add(c.restitution, "restitution");
  add(c.kinematic, "kinematic bodies");
  add(c.axis_drives, "per-axis drives");
  add(c.lifetimes, "bodies that come and go");
  return s.empty() ? "none of rotation, friction, restitution, kinematic bodies, per-axis drives"
                   : s;
}

// Each key's default, as `engines` lists it: "(required)", or its default and those that follow
// another key's value.
std::string default_text(const KeyDef& k) {
  std::string def = k.default_value.empty() ? "(required)" : k.default_value;
  for (const auto& [when, then] : k.default_when)
    def += ", " + then + " if " + k.depends_on + "=" + when;
  return def;
}

std::string values_text(const KeyDef& k) {
  if (k.file) return "a file";
  if (k.text) return "text";
  std::string values;
  for (const std::string& c : k.choices)
    values += (values.empty() ? "" : "|") + c;
  if (!values.empty()) return values;
  return "[" + exact_number(k.min) + ", " + exact_number(k.max) + "]" + (k.integer ? " whole" : "");
}

// The spec's value of `k` where it is not the key's default in that spec, else empty: what the
// spec changes stands out. A file by its name, as labels give it (the canonical line has its path).
std::string given_text(const KeyDef& k, const EngineSpec& spec) {
  const std::string& value = spec.get(k.name);
  std::string def = k.default_value;
  for (const auto& [key, set] : spec.settings) {
    if (key != k.depends_on) continue;
    for (const auto& [when, then] : k.default_when) {
      if (set == when) def = then;
    }
  }
  if (value == def) return "";
  return k.file ? std::filesystem::path(value).filename().string() : value;
}

std::string type_text(const KeyDef& k) {
  if (k.file) return "file";
  if (k.text) return "text";
  if (!k.choices.empty()) return "choice";
  return k.integer ? "integer" : "number";
}

const char* aggregate_text(Aggregate a) {
  switch (a) {
    case Aggregate::kMean:
      return "mean per step";
    case Aggregate::kSum:
      return "sum over the run";
    case Aggregate::kMax:
      return "largest of any step";
    case Aggregate::kLast:
      return "last step";
  }
  return "";
}

int list_engines() {
  std::cout << "Engines (--engines SPEC,SPEC...; a spec is NAME[:key=value,...])\n";
  for (const EngineDef& e : engine_registry()) {
    std::cout << "\n" << e.name << ": " << e.description << "\n";
    if (!e.caveat.empty()) std::cout << "  caveat: " << e.caveat << "\n";
    TextTable t({"  key", "default", "values", "meaning"});
    for (const KeyDef& k : e.keys)
      t.add({"  " + k.name, default_text(k), values_text(k), k.help});
    if (e.more_keys) {
      t.add({"  (more)", "", "",
             "the keys its library declares: chainbench engines " + e.name +
                 ":path=FILE lists them"});
    }
    t.wrap_text(kListWidth);
    t.print(std::cout);
    for (const EngineLimit& l : e.limits)
      std::cout << "  limit: " << l.what << ": " << exact_number(l.value) << " " << l.unit << "\n";
    if (!e.defaults.empty()) {
      std::cout << "  canonical default: " << parse_engine_spec(e.name).str() << "\n";
      std::string runs;
      for (const std::string& d : e.defaults)
        runs += (runs.empty() ? "" : ", ") + d;
      std::cout << "  run by default: " << runs << (e.reference ? " (the default reference)" : "")
                << "\n";
      for (const std::string& d : e.defaults)
        std::cout << "  " << d << " can do: " << capabilities(parse_engine_spec(d)) << "\n";
    }
  }
  return 0;
}

// One engine as `text` gives it (a plugin loaded and checked): every key with its type, range,
// default and help, what it can do and what it counts.
int list_engine(const std::string& text) {
  const EngineSpec spec = parse_engine_spec(text);
  const EngineDef& e = engine_def(spec.engine);
  std::cout << spec.label() << ": " << e.description << "\n";
  if (e.spec_name) std::cout << "name: " << e.spec_name(spec) << " (as its library declares it)\n";
  if (!e.caveat.empty()) std::cout << "caveat: " << e.caveat << "\n";
  std::cout << "canonical: " << spec.str() << "\n\nkeys:\n";
  std::vector<KeyDef> keys = e.keys;
  if (e.more_keys) {
    const std::vector<KeyDef> more = e.more_keys(spec);
    keys.insert(keys.end(), more.begin(), more.end());
  }
  TextTable t({"  key", "type", "values", "default", "given", "meaning"});
  for (const KeyDef& k : keys)
    t.add({"  " + k.name, type_text(k), values_text(k), default_text(k), given_text(k, spec),
           k.help});
  t.wrap_text(kListWidth);
  t.print(std::cout);
  std::cout << "\ncan do: " << capabilities(spec) << "\n";
  for (const EngineLimit& l : e.limits)
    std::cout << "limit: " << l.what << ": " << exact_number(l.value) << " " << l.unit << "\n";
  const std::vector<CounterDef> counters = e.spec_counters ? e.spec_counters(spec) : e.counters;
  std::cout << "\ncounters:" << (counters.empty() ? " none" : "") << "\n";
  if (!counters.empty()) {
    TextTable c({"  counter", "over a run", "meaning"});
    for (const CounterDef& d : counters)
      c.add({"  " + d.name, aggregate_text(d.aggregate), d.help});
    c.wrap_text(kListWidth);
    c.print(std::cout);
  }
  return 0;
}

}  // namespace

void add_list_commands(CLI::App& app, int* status) {
  auto suite = std::make_shared<std::string>();
  CLI::App* list = app.add_subcommand("list", "Built-in scenes, their parameters and defaults");
  list->add_option("--suite", *suite,
                   "only the names of a suite's scenes, one a line, in its order: default (what "
                   "scripts/run.sh runs)")
      ->check(CLI::IsMember({"default"}));
  auto metrics = std::make_shared<bool>(false);
  list->add_flag("--metrics", *metrics,
                 "the metrics a run measures, as a Markdown table: key, CSV column, group, unit, "
                 "how the steps make it, how it is read, meaning (docs/output-formats.md §2.5 "
                 "holds this text)")
      ->excludes("--suite");
  list->callback([status, suite, metrics] {
    if (*metrics) {
      std::cout << metric_docs_table();
      *status = 0;
      return;
    }
    if (suite->empty()) {
      *status = list_scenes();
      return;
    }
    for (const std::string& name : default_suite())
      std::cout << name << '\n';
    *status = 0;
  });
  auto spec = std::make_shared<std::string>();
  CLI::App* engines = app.add_subcommand("engines", "Engine specs and their keys");
  // Given empty, SPEC is a mistake (a shell variable that expanded to nothing), as --engines is.
  engines
      ->add_option("spec", *spec,
                   "one engine's spec (e.g. plugin:path=FILE): its keys with type, range, "
                   "default and help, what it can do and what it counts")
      ->check(kEngineSpec);
  engines->callback(
      [status, spec] { *status = spec->empty() ? list_engines() : list_engine(*spec); });
}

}  // namespace chainbench
