// SPDX-License-Identifier: MIT
// Fuzzes what a plugin hands back. A fake plugin, whose table (ABI, size, name, capabilities,
// counters, declared keys, null functions) and every return (worlds, error texts, step codes, body
// counts, states, counter values) come from the fuzzer's bytes, is driven through the plugin engine
// exactly as a loaded library would be. Whatever it returns, chainbench must either refuse it
// with an InputError whose message is short printable text, or go on with finite numbers: a
// state or counter that reaches chainbench is finite, a step accepted returned 0 or 1.
//
// Every string the fake hands out lives in a heap block of exactly the size the contract bounds
// it by (64 bytes for the name, 32 per counter or key name, 128 per description or help, 64 for
// a key's default, error_size for an error), so that ASan
// reports any read past the bound.
#include "byte_reader.h"
#include "engines/plugin_engine.h"
#include "scenes/scene_file.h"
#include "support/input_error.h"

#include <chainbench/engine_plugin.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "plugin_fuzz: %s\n", what);
  std::abort();
}

// One run's fake plugin: the bytes it reads from, and the blocks it has handed out.
struct Fake {
  fuzz::ByteReader bytes{nullptr, 0};
  std::vector<std::unique_ptr<char[]>> blocks;
  int world_tag = 0;  // the address create returns
  int last_step = 0;  // what step last returned
  std::uint32_t body_count = 0;
  std::uint32_t key_count = 0;  // keys the table declares
};
Fake g;

// A block of `bound` bytes holding up to `bound` bytes from the fuzzer: terminated within the
// bound when the fuzzer gives fewer (or a zero), not terminated when it fills the block.
const char* text_block(std::size_t bound) {
  auto block = std::make_unique<char[]>(bound);
  const std::size_t length = g.bytes.flag() ? bound : g.bytes.byte() % bound;
  for (std::size_t i = 0; i < length; ++i)
    block[i] = g.bytes.flag() ? static_cast<char>('a' + g.bytes.pick(26))
                              : static_cast<char>(g.bytes.byte());
  if (length < bound) block[length] = '\0';
  g.blocks.push_back(std::move(block));
  return g.blocks.back().get();
}

// Writes what a failing plugin might into chainbench's error buffer.
void write_error(char* error, std::size_t size) {
  if (!error || size == 0 || g.bytes.flag()) return;  // leaves chainbench's empty buffer
  const std::size_t length = g.bytes.flag() ? size : g.bytes.byte() % size;
  for (std::size_t i = 0; i < length; ++i)
    error[i] = static_cast<char>(g.bytes.flag() ? 'a' + g.bytes.pick(26) : g.bytes.byte());
  if (length < size) error[length] = '\0';
}

// A number as a plugin might return it: mostly ordinary, sometimes not finite or extreme.
double number() {
  switch (g.bytes.pick(16)) {
    case 0:
      return std::nan("");
    case 1:
      return INFINITY;
    case 2:
      return -INFINITY;
    case 3:
      return 1e308;
    case 4:
      return 5e-324;
    default:
      return g.bytes.grid(-8.0, 0.0625);
  }
}

cb_world* fake_create(const cb_world_desc* desc, char* error, std::size_t error_size) {
  require(desc && desc->abi == CHAINBENCH_PLUGIN_ABI, "create got no description, or another ABI");
  g.body_count = desc->body_count;
  // The scene below: 8 steps, player (body 1) driven on both axes, every body named.
  require(desc->steps == 8 && desc->driver_count == 1 && desc->drivers[0].body == 1 &&
              desc->drivers[0].axes == (CB_AXIS_X | CB_AXIS_Y) && desc->drivers[0].velocity[0] == 2,
          "create got another scene's steps or drivers");
  for (std::uint32_t i = 0; i < desc->body_count; ++i)
    require(desc->bodies[i].name && desc->bodies[i].name[0], "a body came without its name");
  require(desc->setting_count == g.key_count, "create got other settings than the declared keys");
  if (g.bytes.pick(8) == 0) {
    write_error(error, error_size);
    return nullptr;
  }
  return reinterpret_cast<cb_world*>(&g.world_tag);
}

int fake_set_velocity(cb_world* world, std::uint32_t body, double, double, std::uint32_t) {
  require(world == reinterpret_cast<cb_world*>(&g.world_tag), "set_velocity on a foreign world");
  require(body < g.body_count, "set_velocity of a body the scene does not have");
  return g.bytes.pick(16) == 0 ? 1 : 0;
}

int fake_step(cb_world* world, char* error, std::size_t error_size) {
  require(world == reinterpret_cast<cb_world*>(&g.world_tag), "step on a foreign world");
  static constexpr int kCodes[] = {0, 0, 0, 0, 0, 1, -1, 2, INT_MAX, INT_MIN};
  g.last_step = kCodes[g.bytes.pick(sizeof kCodes / sizeof kCodes[0])];
  if (g.last_step < 0) write_error(error, error_size);
  return g.last_step;
}

std::uint32_t fake_read_state(const cb_world*, double* positions, double* velocities,
                              double* angles, std::uint32_t capacity) {
  for (std::uint32_t i = 0; i < capacity; ++i) {
    if (positions) positions[2 * i] = number(), positions[2 * i + 1] = number();
    if (velocities) velocities[2 * i] = number(), velocities[2 * i + 1] = number();
    if (angles) angles[i] = g.bytes.flag() ? number() : 0.0;
  }
  switch (g.bytes.pick(16)) {
    case 0:
      return capacity + 1;
    case 1:
      return capacity - 1;  // wraps to UINT32_MAX for an empty world
    case 2:
      return 0;
    default:
      return capacity;
  }
}

std::uint32_t counter_count = 0;
void fake_read_counters(const cb_world*, double* values) {
  for (std::uint32_t k = 0; k < counter_count; ++k)
    values[k] = number();
}

// The scene has no bodies that come and go: chainbench must never call it.
int fake_change(cb_world*, std::uint32_t) {
  require(false, "add_body or remove_body called for a scene whose bodies stay");
  return 1;
}

void fake_destroy(cb_world* world) {
  require(world == reinterpret_cast<cb_world*>(&g.world_tag), "destroy of a foreign world");
}

// A string the fake hands out: mostly one of a few a key might hold, else the fuzzer's text.
const char* key_text(std::size_t bound) {
  static const char* const kUsual[] = {"iterations", "4", "0.5", "-3", "1e3", "fast", ""};
  return g.bytes.pick(4) == 0 ? text_block(bound) : kUsual[g.bytes.pick(7)];
}

// Up to 5 keys (and, rarely, more than the 32 allowed); the spec the fuzzer runs gives
// iterations=4, which the first key accepts when it is an integer or number named iterations.
void fake_keys(cb_engine& t, std::vector<cb_key>& keys) {
  const std::uint32_t count = g.bytes.pick(64) == 0 ? 33 : g.bytes.pick(6);
  for (std::uint32_t k = 0; k < count; ++k) {
    cb_key key{};
    key.name = g.bytes.pick(32) == 0 ? nullptr : key_text(32);
    key.type = static_cast<std::int32_t>(g.bytes.pick(4)) - (g.bytes.pick(32) == 0 ? 9 : 0);
    key.min = g.bytes.flag() ? 0.0 : number();
    key.max = g.bytes.flag() ? 10.0 : number();
    key.default_value = g.bytes.pick(32) == 0 ? nullptr : key_text(64);
    key.help = g.bytes.pick(32) == 0 ? nullptr : text_block(128);
    keys.push_back(key);
  }
  t.key_count = g.key_count = count;
  t.keys = g.bytes.pick(32) == 0 ? nullptr : keys.data();
}

// The table, field by field from the bytes; mostly valid, so that runs get past the checks.
cb_engine fake_table(std::vector<cb_counter>& counters, std::vector<cb_key>& keys) {
  cb_engine t{};
  t.abi = g.bytes.pick(32) == 0 ? g.bytes.byte() : CHAINBENCH_PLUGIN_ABI;
  t.size = g.bytes.pick(32) == 0 ? g.bytes.byte() : static_cast<std::uint32_t>(sizeof(cb_engine));
  t.name = g.bytes.pick(8) == 0 ? nullptr : text_block(64);
  t.capabilities = g.bytes.pick(16) == 0 ? 0xffffffffu : g.bytes.byte() & 63u;
  counter_count = static_cast<std::uint32_t>(g.bytes.pick(20));
  for (std::uint32_t k = 0; k < counter_count; ++k) {
    cb_counter c{};
    c.name = g.bytes.pick(32) == 0 ? nullptr : text_block(32);
    c.description = g.bytes.pick(32) == 0 ? nullptr : text_block(128);
    c.aggregate = static_cast<std::int32_t>(g.bytes.pick(g.bytes.pick(16) == 0 ? 256 : 4)) -
                  (g.bytes.pick(64) == 0 ? 128 : 0);
    counters.push_back(c);
  }
  t.counter_count = counter_count;
  t.counters = g.bytes.pick(32) == 0 ? nullptr : counters.data();
  fake_keys(t, keys);
  t.create = fake_create;
  t.set_velocity = fake_set_velocity;
  t.step = fake_step;
  t.read_state = fake_read_state;
  t.read_counters = fake_read_counters;
  t.destroy = fake_destroy;
  t.add_body = g.bytes.pick(8) == 0 ? nullptr : fake_change;
  t.remove_body = g.bytes.pick(8) == 0 ? nullptr : fake_change;
  switch (g.bytes.pick(64)) {  // now and then one function missing
    case 0:
      t.create = nullptr;
      break;
    case 1:
      t.step = nullptr;
      break;
    case 2:
      t.read_state = nullptr;
      break;
    case 3:
      t.read_counters = nullptr;
      break;
    case 4:
      t.destroy = nullptr;
      break;
    case 5:
      t.set_velocity = nullptr;
      break;
    default:
      break;
  }
  return t;
}

// A message a refusal prints: one readable line, of a length a terminal can show.
void require_readable(const char* message) {
  const std::size_t length = std::strlen(message);
  require(length > 0 && length < 1000, "a refusal's message is empty or over 1000 bytes");
  for (std::size_t i = 0; i < length; ++i) {
    const auto c = static_cast<unsigned char>(message[i]);
    require(c >= 0x20 && c <= 0x7e, "a refusal's message holds a non-printable byte");
  }
}

const chainbench::Scene& scene() {
  // Three boxes, one driven along x, on a ground: set_velocity, step and read_state all run.
  static const chainbench::Scene s = chainbench::parse_scene(R"({
    "schema": 1, "name": "plugin_fuzz", "dt": 0.0166, "steps": 8,
    "bodies": [
      {"name": "ground", "type": "static", "center": [0, -1], "half_extents": [5, 0.5]},
      {"name": "player", "type": "dynamic", "center": [0, 0], "half_extents": [0.5, 0.5], "mass": 1},
      {"name": "crate", "type": "dynamic", "center": [1, 0], "half_extents": [0.5, 0.5], "mass": 1}],
    "drivers": [{"body": "player", "kind": "velocity", "velocity": [2, 0]}]})",
                                                             "plugin_fuzz.json");
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chainbench;
  g = Fake{};
  g.bytes = fuzz::ByteReader(data, size);
  std::vector<cb_counter> counters;
  std::vector<cb_key> keys;
  const cb_engine table = fake_table(counters, keys);
  const Scene& s = scene();
  try {
    const EngineSpec spec{"plugin", {{"path", "fuzz.so"}, {"iterations", "4"}}};
    const auto engine = make_plugin_engine(&table, "fuzz.so", spec, s);
    // Accepted: the table is what the contract allows.
    require(table.abi == CHAINBENCH_PLUGIN_ABI && table.size == sizeof(cb_engine),
            "a table of another ABI or size was accepted");
    require(table.counter_count <= 16, "more than 16 counters were accepted");
    require(!(table.capabilities & CB_CAN_LIFETIMES) || (table.add_body && table.remove_body),
            "CB_CAN_LIFETIMES was accepted without add_body and remove_body");
    require(table.key_count <= 32 && table.key_count > 0 && table.keys,
            "a spec key was accepted that the table does not declare, or over 32 keys");
    require(engine->counter_defs().size() == table.counter_count, "counters lost or invented");
    for (std::uint32_t k = 0; k < table.counter_count; ++k) {
      require(
          table.counters[k].aggregate >= CB_AGG_MEAN && table.counters[k].aggregate <= CB_AGG_LAST,
          "a counter of an unknown aggregate was accepted");
    }
    BodyState state(s.bodies.size());
    for (int step = 0; step < s.steps; ++step) {
      engine->step(step);
      require(g.last_step == 0 || g.last_step == 1, "a step code outside 0 and 1 was accepted");
      require(engine->degraded() == (g.last_step == 1), "a cut-short step was not kept");
      engine->read_state(state);
      for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        require(std::isfinite(state.position[i].x) && std::isfinite(state.position[i].y) &&
                    std::isfinite(state.velocity[i].x) && std::isfinite(state.velocity[i].y) &&
                    std::isfinite(state.angle[i]),
                "a non-finite state was accepted");
      }
      for (const double value : engine->counters())
        require(std::isfinite(value), "a non-finite counter was accepted");
    }
  } catch (const InputError& refused) {
    require_readable(refused.what());  // refused by name: the right answer
  }
  return 0;
}
