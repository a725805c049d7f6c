// chainbench list, chainbench engines: what can be run, and with which keys.
#include "commands.h"
#include "engine_spec.h"
#include "scene_library.h"
#include "text_table.h"

#include <iostream>

namespace chainbench {
namespace {

std::string range(const SceneParam& p) {
  return "[" + fmt_g(p.min, 6) + ", " + fmt_g(p.max, 6) + "]" + (p.integer ? " whole" : "");
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
    TextTable t({"    key", "default", "range", "meaning"});
    for (const SceneParam& p : r.params)
      t.add({"    " + p.key, fmt_g(p.value, 6), range(p), p.help});
    t.add({"    steps", std::to_string(r.steps), "[1, 1e+07] whole", "steps to run"});
    t.print(std::cout);
  }
  std::cout
      << "\nEvery scene also takes dt (1/60 s), friction (0), restitution (0), rotation (0) and\n"
         "offset (0 m: moves the whole scene along x and y).\n";
  return 0;
}

int list_engines() {
  std::cout << "Engines (--engines SPEC,SPEC...; a spec is NAME[:key=value,...])\n";
  for (const EngineInfo& e : engine_catalog()) {
    std::cout << "\n" << e.name << ": " << e.description << "\n";
    TextTable t({"  key", "default", "values", "meaning"});
    for (const EngineKey& k : e.keys) {
      std::string values;
      for (const std::string& c : k.choices)
        values += (values.empty() ? "" : "|") + c;
      if (values.empty()) values = "[" + std::to_string(k.min) + ", " + std::to_string(k.max) + "]";
      t.add({"  " + k.name, k.default_value.empty() ? "(see meaning)" : k.default_value, values,
             k.help});
    }
    t.print(std::cout);
    std::cout << "  canonical default: " << parse_engine_spec(e.name).str() << "\n";
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
