// SPDX-License-Identifier: MIT
#include "engines/registry.h"
#include "support/number_text.h"

#include "support/input_error.h"
#include "support/text_table.h"

#include <algorithm>
#include <charconv>

namespace chainbench {

// Each adapter file defines register_NAME(); bench/CMakeLists.txt lists them in engine_list.inc.
#define CHAINBENCH_ENGINE(name) EngineDef register_##name();
#include "engine_list.inc"
#undef CHAINBENCH_ENGINE

KeyDef choice_key(std::string name, std::string default_value, std::vector<std::string> choices,
                  std::string help) {
  KeyDef k;
  k.name = std::move(name);
  k.default_value = std::move(default_value);
  k.choices = std::move(choices);
  k.help = std::move(help);
  return k;
}

KeyDef whole_key(std::string name, long long default_value, long long min, long long max,
                 std::string help) {
  KeyDef k;
  k.name = std::move(name);
  k.default_value = std::to_string(default_value);
  k.min = static_cast<double>(min);
  k.max = static_cast<double>(max);
  k.help = std::move(help);
  return k;
}

KeyDef number_key(std::string name, double default_value, double min, double max,
                  std::string help) {
  KeyDef k;
  k.name = std::move(name);
  k.default_value = exact_number(default_value);
  k.min = min;
  k.max = max;
  k.integer = false;
  k.help = std::move(help);
  return k;
}

KeyDef file_key(std::string name, std::string help) {
  KeyDef k;
  k.name = std::move(name);
  k.file = true;
  k.help = std::move(help);
  return k;
}

KeyDef text_key(std::string name, std::string default_value, std::string help) {
  KeyDef k;
  k.name = std::move(name);
  k.default_value = std::move(default_value);
  k.text = true;
  k.help = std::move(help);
  return k;
}

const std::vector<EngineDef>& engine_registry() {
  static const std::vector<EngineDef> registry = {
#define CHAINBENCH_ENGINE(name) register_##name(),
#include "engine_list.inc"
#undef CHAINBENCH_ENGINE
  };
  return registry;
}

const EngineDef& engine_def(std::string_view name) {
  const auto& registry = engine_registry();
  const auto it = std::find_if(registry.begin(), registry.end(),
                               [&](const EngineDef& e) { return e.name == name; });
  if (it == registry.end()) {
    std::string known;
    for (const EngineDef& e : registry)
      known += (known.empty() ? "" : ", ") + e.name;
    throw InputError("unknown engine \"" + std::string(name) + "\" (known: " + known + ")");
  }
  return *it;
}

std::string missing_capability(const EngineSpec& spec, const Scene& scene) {
  const Capabilities can = engine_def(spec.engine).capabilities(spec);
  const std::string who = spec.label();
  if (scene.rotation && !can.rotation)
    return who + " cannot turn bodies, and the scene rotates them";
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const SceneBody& b = scene.bodies[i];
    const std::string at = "bodies[" + std::to_string(i) + "] (" + b.name + ")";
    if (!can.friction && scene.friction_of(b) > 0.0) {
      return who + " has no friction, and " + at + " has friction " +
             exact_number(scene.friction_of(b));
    }
    if (!can.restitution && scene.restitution_of(b) > 0.0) {
      return who + " does not bounce, and " + at + " has restitution " +
             exact_number(scene.restitution_of(b));
    }
    if (!can.kinematic && b.kind == BodyKind::kKinematic) {
      return who + " has no kinematic bodies, and " + at + " is one";
    }
    if (!can.filtering && (b.category_bits != 0x0001 || b.mask_bits != 0xFFFF)) {
      return who + " cannot filter collisions, and " + at + " has category_bits " +
             std::to_string(b.category_bits) + " and mask_bits " + std::to_string(b.mask_bits);
    }
    if (!can.belts && (b.surface_velocity.x != 0.0 || b.surface_velocity.y != 0.0)) {
      return who + " has no conveyors, and " + at + " has surface_velocity " +
             exact_number(b.surface_velocity.x);
    }
    if (!can.lifetimes && b.comes_or_goes()) {
      return who + " cannot add or remove bodies during a run, and " + at + " " +
             (b.from_step > 0 ? "enters at step " + std::to_string(b.from_step)
                              : "leaves at step " + std::to_string(b.to_step));
    }
  }
  for (std::size_t i = 0; i < scene.drivers.size(); ++i) {
    const Driver& d = scene.drivers[i];
    if (!can.axis_drives && !(d.hold_x && d.hold_y)) {
      return who + " cannot hold one axis of a velocity, and drivers[" + std::to_string(i) +
             "] leaves " + (d.hold_x ? "y" : "x") + " free";
    }
  }
  return {};
}

std::unique_ptr<Engine> make_engine(const EngineSpec& spec, const Scene& scene) {
  if (std::string why = missing_capability(spec, scene); !why.empty()) {
    throw InputError("scene " + scene.name + ": " + why);
  }
  return engine_def(spec.engine).make(spec, scene);
}

std::vector<EngineSpec> default_engines() {
  std::vector<EngineSpec> out;
  for (const EngineDef& e : engine_registry()) {
    for (const std::string& spec : e.defaults)
      out.push_back(parse_engine_spec(spec));
  }
  return out;
}

EngineSpec default_reference() {
  for (const EngineDef& e : engine_registry()) {
    if (e.reference) return parse_engine_spec(e.name);
  }
  return parse_engine_spec(engine_registry().front().name);
}

EngineSpec accurate_reference() {
  const EngineSpec reference = default_reference();
  const std::string& accurate = engine_def(reference.engine).accurate;
  return accurate.empty() ? reference : parse_engine_spec(accurate);
}

std::vector<EngineSpec> default_sweep_grid() {
  std::vector<EngineSpec> grid;
  for (const EngineDef& e : engine_registry()) {
    if (e.defaults.empty()) continue;
    grid.push_back(parse_engine_spec(e.name));
    for (const std::string& knob : e.sweep) {
      for (const EngineSpec& spec : parse_grid(e.name + ":" + knob)) {
        if (std::find(grid.begin(), grid.end(), spec) == grid.end()) grid.push_back(spec);
      }
    }
  }
  return grid;
}

bool is_gate(const EngineSpec& spec) {
  const EngineDef& e = engine_def(spec.engine);
  return !e.gate.empty() && parse_engine_spec(e.gate) == spec;
}

std::string known_failure(const EngineSpec& spec, const std::string& stress_case,
                          const std::string& verdict) {
  if (!is_gate(spec)) return {};
  for (const EngineDef::KnownFailure& k : engine_def(spec.engine).known_failures) {
    if (k.stress_case == stress_case && k.verdict == verdict) return k.reason;
  }
  return {};
}

}  // namespace chainbench
