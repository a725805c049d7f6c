// SPDX-License-Identifier: MIT
// The engines chainbench can run. Each adapter file registers one engine (its name, keys,
// capabilities, counters, defaults and factory), and nothing else in the harness names an engine:
// spec parsing, `chainbench engines`, default engine lists, sweep grids, benchmarks and reports all
// read this registry. Adding an engine is one adapter file and one CMake line,
// `chainbench_engine(NAME FILE)` in bench/CMakeLists.txt.
#pragma once

#include "engines/engine.h"
#include "engines/engine_spec.h"
#include "model/scene.h"

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace chainbench {

// A key of an engine spec, typed and ranged, with its default.
struct KeyDef {
  std::string name;
  std::string default_value;
  std::vector<std::string> choices;  // empty: a number in [min, max], a file or a text
  double min = 0.0;
  double max = 0.0;
  bool integer = true;
  bool file = false;  // a path to a file, kept as an absolute path; no default: required
  bool text = false;  // any non-empty text, kept as given
  std::string help;
  // A default that follows another key: while `depends_on` has value `first`, it is `second`.
  std::string depends_on;
  std::vector<std::pair<std::string, std::string>> default_when;
};

// Keys of the three kinds.
KeyDef choice_key(std::string name, std::string default_value, std::vector<std::string> choices,
                  std::string help);
KeyDef whole_key(std::string name, long long default_value, long long min, long long max,
                 std::string help);
KeyDef number_key(std::string name, double default_value, double min, double max, std::string help);
KeyDef file_key(std::string name, std::string help);
KeyDef text_key(std::string name, std::string default_value, std::string help);

// What an engine can simulate; a scene that needs more is refused by name, not run wrong.
struct Capabilities {
  bool rotation = false;     // bodies turn (scene "rotation": true)
  bool friction = false;     // Coulomb friction between boxes
  bool restitution = false;  // bounces
  bool kinematic = false;    // kinematic bodies (moving, infinite mass)
  bool axis_drives = false;  // a driver that holds one axis and leaves the other free
  bool lifetimes = false;    // bodies added and removed during a run (SceneBody::from_step)
  bool filtering = false;    // collision filtering (SceneBody::category_bits, mask_bits)
  bool belts = false;        // conveyors (SceneBody::surface_velocity)
};

// A limit an engine imposes on every world it builds, whatever the scene asks: Box2D 2.4 moves no
// body more than 2 m in one of its steps (b2_maxTranslation). Listed by `chainbench engines`; a
// run whose scene asks for more is noted under the table, since that engine cannot be right there.
struct EngineLimit {
  std::string what;  // "moves no body more than this in one world step (b2_maxTranslation)"
  double value = 0.0;
  std::string unit;  // of value: "m", "m/s"
  // The fastest any body can move in a run of `spec` on `scene`, m/s (a per-step limit over the
  // engine's own step, sub-steps included).
  std::function<double(const EngineSpec&, const Scene&)> speed;
};

struct EngineDef {
  std::string name;
  std::string description;
  std::vector<KeyDef> keys;
  // Keys that follow from the declared ones (a plugin's, which its library declares): checked,
  // defaulted and listed as `keys` are, after them. Called with the declared keys parsed.
  std::function<std::vector<KeyDef>(const EngineSpec&)> more_keys;
  std::function<Capabilities(const EngineSpec&)> capabilities;
  std::vector<CounterDef> counters;  // what its engines count
  // What an engine of `spec` counts when it follows from the spec (a plugin's, from its library);
  // when set, it stands for `counters`.
  std::function<std::vector<CounterDef>(const EngineSpec&)> spec_counters;
  // The name the engine behind `spec` gives itself, when it is not chainbench's (a plugin's, as
  // its library declares it), for `chainbench engines SPEC`; unset for the others.
  std::function<std::string(const EngineSpec&)> spec_name;
  // How its times must be read, said beside every figure that quotes them (run JSON "caveat",
  // `chainbench engines`, the benchmark's context, the report's and README's ratios); or empty.
  std::string caveat;
  std::string stats_block;            // also writes its counters under this run-JSON key
  std::vector<std::string> defaults;  // specs run when a command is given no engine list
  bool reference = false;             // the default reference of `run`
  // Its code is not the harness' own (plugins): `run` and `sweep` run it in a child process, so
  // that a crash or a hang in it is its verdict rather than the end of the command.
  bool isolated = false;
  std::string accurate;            // a setting finer than any sweep point: a sweep reference
  std::vector<std::string> sweep;  // default sweep, one knob at a time: "vel_iters=1,2,4"
  // A setting that must be right: `stress` fails when its verdict on a case is anything but ok or
  // budget, except where a known failure lists that very case and verdict, with its reason.
  std::string gate;
  struct KnownFailure {
    std::string stress_case;  // "projectile speed=500"
    std::string verdict;      // the one verdict excused: "tunnelled"
    std::string reason;
  };
  std::vector<KnownFailure> known_failures;
  // The specs the benchmark program runs, each with the largest scene it is run on (bodies).
  std::vector<std::pair<std::string, std::size_t>> benchmarks;
  std::function<std::unique_ptr<Engine>(const EngineSpec&, const Scene&)> make;
  std::vector<EngineLimit> limits;  // what it caps, for every spec
};

// Every registered engine, in the order bench/CMakeLists.txt lists them.
const std::vector<EngineDef>& engine_registry();
// The engine named `name`, or InputError naming the known ones.
const EngineDef& engine_def(std::string_view name);

// Builds the engine `spec` names for `scene`. Throws InputError when the scene needs something
// the engine cannot do (missing_capability), or when the engine refuses the scene.
std::unique_ptr<Engine> make_engine(const EngineSpec& spec, const Scene& scene);
// Why `spec` cannot run `scene` ("it has no friction, and bodies[3] has friction 0.5"), or empty.
std::string missing_capability(const EngineSpec& spec, const Scene& scene);

// Every engine's default specs, in registry order: what `run`, `stress` and `sweep` use when no
// list is given.
std::vector<EngineSpec> default_engines();
// The default reference of `run`, and the sweep's (a setting finer than any sweep point).
EngineSpec default_reference();
EngineSpec accurate_reference();
// Every engine's default settings and one knob changed at a time (EngineDef::sweep).
std::vector<EngineSpec> default_sweep_grid();
// Whether `spec` is some engine's gate (EngineDef::gate), and why it is known to end a stress case
// with `verdict` (empty when it is not).
bool is_gate(const EngineSpec& spec);
std::string known_failure(const EngineSpec& spec, const std::string& stress_case,
                          const std::string& verdict);

}  // namespace chainbench
