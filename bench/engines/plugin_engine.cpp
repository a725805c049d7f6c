// SPDX-License-Identifier: MIT
// A user's own resolver, loaded from a shared library through the C ABI of
// bench/include/chainbench/engine_plugin.h: `plugin:path=FILE[,key=value...]`.
//
// What a plugin returns is checked as it comes: a library that cannot be loaded, has no entry
// point, was built for another ABI or gives an incomplete table, a world it cannot build, a step
// that fails, a state of the wrong size or with a non-finite number, each stops the run with a
// message naming the plugin (InputError: exit status 2, or an `error` verdict in stress). A
// library is first loaded and checked in a child process (probe_load), so that one that crashes,
// exits or hangs while loading is refused by name rather than ending chainbench.
#include "engines/plugin_engine.h"
#include "engines/plugin_load.h"
#include "engines/plugin_table.h"
#include "engines/plugin_text.h"
#include "engines/registry.h"
#include "model/drive_schedule.h"
#include "support/child_process.h"
#include "support/input_error.h"
#include "support/text_table.h"

#include <chainbench/engine_plugin.h>

#include <dlfcn.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>

namespace chainbench {
namespace {

constexpr std::size_t kErrorSize = 512;  // the error buffer chainbench hands a plugin
constexpr double kProbeTimeout = 60.0;   // seconds a library may take to load and hand its table

// What a plugin wrote into an error buffer of kErrorSize bytes, as a message may quote it.
std::string plugin_error(const char* error) {
  const PluginText t = read_plugin_text(error, kErrorSize);
  if (t.problem.empty()) return t.text.empty() ? "it gave no reason" : t.text;
  return "its message " + t.problem + ", so it is not shown in full: " + t.shown;
}

// dlopen, the entry function and the table's check, in this process.
Plugin load_checked(const std::string& path) {
  const std::string where = "plugin " + path;
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw InputError(where + ": cannot load it: " + std::string(dlerror()));
  const auto entry = reinterpret_cast<cb_entry_fn>(dlsym(handle, CHAINBENCH_PLUGIN_ENTRY));
  if (!entry) {
    throw InputError(where + ": exports no " + std::string(CHAINBENCH_PLUGIN_ENTRY) +
                     "() (is it a chainbench plugin? see chainbench/engine_plugin.h)");
  }
  const cb_engine* api = entry();
  if (!api) throw InputError(where + ": " + CHAINBENCH_PLUGIN_ENTRY + "() returned null");
  return check_table(api, path);
}

// A stand-in table for a library kept after its probe failed: every capability, no counters and
// no keys, and functions never called (make loads the library itself, in a child process).
const cb_engine* stand_in_table() {
  static const cb_engine table = [] {
    cb_engine t{};
    t.abi = CHAINBENCH_PLUGIN_ABI;
    t.size = sizeof(cb_engine);
    t.capabilities = known_capabilities();
    return t;
  }();
  return &table;
}

bool g_keep_failed_loads = false;
std::vector<std::string> g_failed_loads;

// A library that crashed, exited or hung while it was loaded in its probe: refused as bad input,
// or kept for stress (keep_plugins_that_fail_to_load).
struct LoadFailure : InputError {
  using InputError::InputError;
};

// The load tried first in a child process (child_process.h): a library whose constructor, entry
// function or table crashes, exits or hangs is refused by name (LoadFailure) instead of taking
// chainbench down. A refusal of its table comes back with its own message (InputError).
void probe_load(const std::string& path) {
  const std::string where = "plugin " + path;
  std::string bytes;
  const ChildOutcome o = run_in_child_bytes(
      [&]() -> std::string {
        try {
          load_checked(path);
          return "";
        } catch (const std::exception& e) {
          return std::string("!") + e.what();
        }
      },
      bytes, kProbeTimeout);
  if (o.finished) {
    if (!bytes.empty()) throw InputError(bytes.substr(1));
    return;
  }
  if (o.hang) {
    throw LoadFailure(where + ": hung while loading (no table within " +
                      std::to_string(static_cast<int>(kProbeTimeout)) + " s)");
  }
  if (o.signal != 0) {
    throw LoadFailure(where + ": crashed while loading: " + signal_text(o.signal) +
                      (o.out_of_memory ? ", out of memory" : ""));
  }
  throw LoadFailure(where + ": exited while loading (status " + std::to_string(o.exit_status) +
                    ")");
}

Plugin open_plugin(const std::string& path) {
  const std::string where = "plugin " + path;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(where + ": no such file");
  if (std::filesystem::is_directory(path, ec))
    throw InputError(where + ": is a directory, not a shared library");
  try {
    probe_load(path);
  } catch (const LoadFailure& e) {
    const std::string why = e.what();
    if (!g_keep_failed_loads) throw;
    g_failed_loads.push_back(why);
    Plugin p;
    p.path = path;
    p.name = "(not loaded)";
    p.api = stand_in_table();
    p.load_failure = why;
    return p;
  }
  return load_checked(path);
}
// Loads each library once.
std::shared_ptr<const Plugin> load_plugin(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const Plugin>> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = loaded[path];
  if (!slot) slot = std::make_shared<const Plugin>(open_plugin(path));
  return slot;
}

cb_body to_plugin(const Scene& scene, const SceneBody& b) {
  cb_body out{};
  out.kind = b.kind == BodyKind::kStatic      ? CB_STATIC
             : b.kind == BodyKind::kKinematic ? CB_KINEMATIC
                                              : CB_DYNAMIC;
  out.center[0] = b.center.x, out.center[1] = b.center.y;
  out.half_extents[0] = b.half_extents.x, out.half_extents[1] = b.half_extents.y;
  out.mass = b.kind == BodyKind::kDynamic ? b.mass : 0.0;
  out.velocity[0] = b.kind == BodyKind::kStatic ? 0.0 : b.velocity.x;
  out.velocity[1] = b.kind == BodyKind::kStatic ? 0.0 : b.velocity.y;
  out.gravity_scale = b.gravity_scale;
  out.friction = scene.friction_of(b);
  out.restitution = scene.restitution_of(b);
  out.from_step = std::clamp(b.from_step, 0, INT32_MAX);
  out.to_step = std::clamp(b.to_step, 0, INT32_MAX);
  return out;
}

class PluginEngine final : public Engine {
 public:
  PluginEngine(std::shared_ptr<const Plugin> plugin, const EngineSpec& spec, const Scene& scene)
      : plugin_(std::move(plugin)),
        drives_(scene),
        names_(scene.bodies.size()),
        in_world_(scene.bodies.size()),
        positions_(2 * scene.bodies.size()),
        velocities_(2 * scene.bodies.size()),
        counters_(plugin_->counters.size()) {
    std::vector<cb_body> bodies;
    bodies.reserve(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      names_[i] = scene.bodies[i].name;
      in_world_[i] = scene.bodies[i].from_step == 0;
      bodies.push_back(to_plugin(scene, scene.bodies[i]));
      bodies.back().name = names_[i].c_str();
    }
    std::vector<cb_driver> drivers;
    for (const Driver& d : scene.drivers) {
      cb_driver out{};
      out.body = static_cast<std::uint32_t>(d.body);
      out.axes =
          (d.hold_x ? std::uint32_t{CB_AXIS_X} : 0u) | (d.hold_y ? std::uint32_t{CB_AXIS_Y} : 0u);
      out.velocity[0] = d.hold_x ? d.velocity.x : 0.0;
      out.velocity[1] = d.hold_y ? d.velocity.y : 0.0;
      out.from_step = std::clamp(d.from_step, 0, INT32_MAX);
      out.to_step = std::clamp(d.to_step, 0, INT32_MAX);
      drivers.push_back(out);
    }
    std::vector<cb_setting> settings;
    for (const auto& [key, value] : spec.settings) {
      if (key != "path") settings.push_back({key.c_str(), value.c_str()});
    }
    cb_world_desc desc{};
    desc.abi = CHAINBENCH_PLUGIN_ABI;
    desc.body_count = static_cast<std::uint32_t>(bodies.size());
    desc.gravity[0] = scene.gravity.x, desc.gravity[1] = scene.gravity.y;
    desc.dt = scene.dt;
    desc.rotation = scene.rotation ? 1 : 0;
    desc.bodies = bodies.data();
    desc.setting_count = static_cast<std::uint32_t>(settings.size());
    desc.settings = settings.data();
    desc.steps = scene.steps;
    desc.driver_count = static_cast<std::uint32_t>(drivers.size());
    desc.drivers = drivers.data();
    char error[kErrorSize] = "";
    world_ = plugin_->api->create(&desc, error, sizeof error);
    if (!world_) {
      throw InputError(describe(*plugin_) + ": could not build scene " + scene.name + ": " +
                       plugin_error(error));
    }
  }

  ~PluginEngine() override { plugin_->api->destroy(world_); }
  PluginEngine(const PluginEngine&) = delete;
  PluginEngine& operator=(const PluginEngine&) = delete;

  void step(int step_index) override {
    drives_.advance(step_index);
    for (const Drive& d : drives_.active()) {
      const std::uint32_t axes =
          (d.hold_x ? std::uint32_t{CB_AXIS_X} : 0u) | (d.hold_y ? std::uint32_t{CB_AXIS_Y} : 0u);
      if (plugin_->api->set_velocity(world_, static_cast<std::uint32_t>(d.body), d.velocity.x,
                                     d.velocity.y, axes) != 0) {
        throw InputError(describe(*plugin_) + ": refused to set the velocity of body " +
                         names_[d.body] + " at step " + std::to_string(step_index));
      }
    }
    char error[kErrorSize] = "";
    const int rc = plugin_->api->step(world_, error, sizeof error);
    // Counted from 1, as verdicts count "at step N": the state after N steps.
    if (rc < 0) {
      throw InputError(describe(*plugin_) + ": step " + std::to_string(step_index + 1) +
                       " failed: " + plugin_error(error));
    }
    if (rc > 1) {
      throw InputError(describe(*plugin_) + ": step " + std::to_string(step_index + 1) +
                       " returned " + std::to_string(rc) +
                       ", which the plugin contract does not allow (0, 1 when cut short, or "
                       "negative on error)");
    }
    degraded_ = rc == 1;
    steps_ = step_index + 1;
  }

  void read_state(BodyState& out) const override {
    const auto n = static_cast<std::uint32_t>(names_.size());
    const std::uint32_t held = plugin_->api->read_state(world_, positions_.data(),
                                                        velocities_.data(), out.angle.data(), n);
    if (held != n) {
      throw InputError(describe(*plugin_) + ": its world holds " + std::to_string(held) +
                       " bodies, the scene " + std::to_string(n));
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!in_world_[i]) continue;  // its entry is the plugin's to leave
      const double values[5] = {positions_[2 * i], positions_[2 * i + 1], velocities_[2 * i],
                                velocities_[2 * i + 1], out.angle[i]};
      for (const double v : values) {
        if (!std::isfinite(v)) {
          throw InputError(describe(*plugin_) + ": returned a non-finite state for body " +
                           names_[i]);
        }
      }
      out.position[i] = {positions_[2 * i], positions_[2 * i + 1]};
      out.velocity[i] = {velocities_[2 * i], velocities_[2 * i + 1]};
    }
  }

  std::span<const CounterDef> counter_defs() const override { return plugin_->counters; }
  std::span<const double> counters() const override {
    if (counters_.empty()) return counters_;
    plugin_->api->read_counters(world_, counters_.data());
    for (std::size_t k = 0; k < counters_.size(); ++k) {
      if (!std::isfinite(counters_[k])) {
        throw InputError(describe(*plugin_) + ": counter " + plugin_->counters[k].name + " is " +
                         (std::isnan(counters_[k]) ? "NaN" : "infinite") + " after step " +
                         std::to_string(steps_) + " (a counter must be a finite number)");
      }
    }
    return counters_;
  }
  bool degraded() const override { return degraded_; }
  // Called only for a plugin with CB_CAN_LIFETIMES, whose table then has both (check_table).
  void add_body(std::size_t index) override { change(index, true); }
  void remove_body(std::size_t index) override { change(index, false); }

 private:
  void change(std::size_t index, bool add) {
    const auto body = static_cast<std::uint32_t>(index);
    const int rc =
        add ? plugin_->api->add_body(world_, body) : plugin_->api->remove_body(world_, body);
    if (rc != 0) {
      throw InputError(describe(*plugin_) + ": refused to " + (add ? "add" : "remove") + " body " +
                       names_[index] + " (" + (add ? "add_body" : "remove_body") + " returned " +
                       std::to_string(rc) + ")");
    }
    in_world_[index] = add ? 1 : 0;
  }

  std::shared_ptr<const Plugin> plugin_;  // shared: the loaded library outlives every world
  cb_world* world_ = nullptr;
  DriveSchedule drives_;
  std::vector<std::string> names_;
  std::vector<char> in_world_;  // per body: in the plugin's world now
  mutable std::vector<double> positions_, velocities_, counters_;
  bool degraded_ = false;
  int steps_ = 0;  // steps taken, for messages
};

}  // namespace

std::unique_ptr<Engine> make_plugin_engine(const cb_engine* table, const std::string& label,
                                           const EngineSpec& spec, const Scene& scene) {
  if (!table) throw InputError("plugin " + label + ": its table is null");
  auto plugin = std::make_shared<const Plugin>(check_table(table, label));
  // As the spec parser would: every setting a declared key's, checked, defaults filled in.
  EngineSpec checked{spec.engine, {}};
  std::vector<std::pair<std::string, std::string>> given;
  for (const auto& setting : spec.settings)
    (setting.first == "path" ? checked.settings : given).push_back(setting);
  add_key_settings("engine spec \"" + cut_for_message(spec.str()) + "\"", plugin->keys, given,
                   checked);
  return std::make_unique<PluginEngine>(std::move(plugin), checked, scene);
}

EngineDef register_plugin() {
  EngineDef e;
  e.name = "plugin";
  e.description =
      "your own resolver, from a shared library built against chainbench/engine_plugin.h";
  e.keys = {file_key("path", "the plugin's shared library (.so)")};
  e.more_keys = [](const EngineSpec& spec) { return load_plugin(spec.get("path"))->keys; };
  e.spec_counters = [](const EngineSpec& spec) { return load_plugin(spec.get("path"))->counters; };
  e.spec_name = [](const EngineSpec& spec) { return load_plugin(spec.get("path"))->name; };
  e.isolated = true;
  e.capabilities = [](const EngineSpec& spec) {
    const std::uint32_t can = load_plugin(spec.get("path"))->api->capabilities;
    Capabilities c;
    c.rotation = (can & CB_CAN_ROTATE) != 0;
    c.friction = (can & CB_CAN_FRICTION) != 0;
    c.restitution = (can & CB_CAN_RESTITUTION) != 0;
    c.kinematic = (can & CB_CAN_KINEMATIC) != 0;
    c.axis_drives = (can & CB_CAN_AXIS_DRIVES) != 0;
    c.lifetimes = (can & CB_CAN_LIFETIMES) != 0;  // with add_body and remove_body (check_table)
    c.filtering = false;  // cb_body (ABI 2) carries no filter bits nor belts: such scenes are
    c.belts = false;      // refused
    return c;
  };
  e.make = [](const EngineSpec& spec, const Scene& scene) -> std::unique_ptr<Engine> {
    auto plugin = load_plugin(spec.get("path"));
    if (!plugin->load_failure.empty()) {
      // Kept for stress, whose cases run in child processes: load it here as its probe did,
      // where its crash is this case's.
      load_checked(plugin->path);
      throw InputError(plugin->load_failure);  // it failed only in its probe
    }
    return std::make_unique<PluginEngine>(std::move(plugin), spec, scene);
  };
  // Without CB_CAN_LIFETIMES, missing_capability refuses scenes whose bodies come and go.
  return e;
}

void keep_plugins_that_fail_to_load(bool keep) {
  g_keep_failed_loads = keep;
}

std::vector<std::string> plugins_that_failed_to_load() {
  return g_failed_loads;
}

}  // namespace chainbench
