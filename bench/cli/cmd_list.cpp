// chainbench list, chainbench engines: what can be run, and with which keys.
#include "commands.h"
#include "engine_spec.h"
#include "registry.h"
#include "scene_library.h"
#include "text_table.h"

#include <iostream>

namespace chainbench {
namespace {

std::string range(const SceneParam& p) {
  return "[" + fmt_exact(p.min) + ", " + fmt_exact(p.max) + "]" + (p.integer ? " whole" : "");
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
      t.add({"    " + p.key, fmt_exact(p.value), range(p), p.help});
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

int list_engines() {
  std::cout << "Engines (--engines SPEC,SPEC...; a spec is NAME[:key=value,...])\n";
  for (const EngineDef& e : engine_registry()) {
    std::cout << "\n" << e.name << ": " << e.description << "\n";
    if (!e.caveat.empty()) std::cout << "  caveat: " << e.caveat << "\n";
    TextTable t({"  key", "default", "values", "meaning"});
    for (const KeyDef& k : e.keys) {
      std::string values;
      for (const std::string& c : k.choices)
        values += (values.empty() ? "" : "|") + c;
      if (k.file) {
        values = "a file";
      } else if (k.text) {
        values = "text";
      } else if (values.empty()) {
        values = "[" + fmt_g(k.min, 9) + ", " + fmt_g(k.max, 9) + "]" + (k.integer ? " whole" : "");
      }
      std::string def = k.default_value.empty() ? "(required)" : k.default_value;
      for (const auto& [when, then] : k.default_when)
        def += ", " + then + " if " + k.depends_on + "=" + when;
      t.add({"  " + k.name, def, values, k.help});
    }
    if (e.more_keys) t.add({"  (more)", "", "", "the keys its library declares"});
    t.print(std::cout);
    for (const EngineLimit& l : e.limits)
      std::cout << "  limit: " << l.what << ": " << fmt_g(l.value, 9) << " " << l.unit << "\n";
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

}  // namespace

void add_list_commands(CLI::App& app, int* status) {
  app.add_subcommand("list", "Built-in scenes, their parameters and defaults")->callback([status] {
    *status = list_scenes();
  });
  app.add_subcommand("engines", "Engine specs and their keys")->callback([status] {
    *status = list_engines();
  });
}

}  // namespace chainbench
