// SPDX-License-Identifier: MIT
#include "scenes/scene_library.h"
#include "support/number_text.h"

#include "support/input_error.h"
#include "support/text_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace chainbench {
namespace {

std::string num(double v) {
  return exact_number(v);  // every digit: a rounded value could look equal to its bound
}

}  // namespace

double SceneParams::get(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) throw std::logic_error("scene recipe reads undeclared parameter " + key);
  return it->second;
}

const std::vector<SceneRecipe>& scene_library() {
  static const std::vector<SceneRecipe> library = [] {
    std::vector<SceneRecipe> all;
    for (auto family : {stacking_scenes, pushing_scenes, level_scenes, moving_scenes,
                        seed2014_scenes, stress_scenes}) {
      for (SceneRecipe& r : family())
        all.push_back(std::move(r));
    }
    return all;
  }();
  return library;
}

const std::vector<std::string>& default_suite() {
  static const std::vector<std::string> suite = {
      "stack",          "pyramid",          "many_pyramids", "mass_ratio_stack",
      "heavy_on_light", "overlap_recovery", "random_pile",   "push_row",
      "push_into_wall", "push_stack",       "squeeze",       "seed_stack",
      "seed_squeeze",   "seed_falling_row", "rain",          "smash",
      "bulldozer",      "spawn_rain"};
  return suite;
}

const SceneRecipe* find_recipe(std::string_view name) {
  for (const SceneRecipe& r : scene_library()) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

std::vector<SceneParam> all_params(const SceneRecipe& recipe) {
  std::vector<SceneParam> params = recipe.params;
  params.push_back(
      {"steps", static_cast<double>(recipe.steps), 1, limits::kMaxSteps, true, "steps to run"});
  params.push_back({"dt", 1.0 / 60.0, limits::kMinDt, limits::kMaxDt, false, "time step, s"});
  params.push_back(
      {"friction", 0.0, 0, limits::kMaxFriction, false, "friction coefficient of every body"});
  params.push_back({"restitution", 0.0, 0, 1, false, "restitution of every body"});
  params.push_back({"rotation", 0.0, 0, 1, true, "1: let bodies rotate, in engines that can"});
  params.push_back(
      {"offset", 0.0, -1e7, 1e7, false, "move the whole scene this far along x and y, m"});
  return params;
}

Scene make_scene(std::string_view name, const std::vector<std::string>& sets) {
  const SceneRecipe* recipe = find_recipe(name);
  if (!recipe) {
    throw InputError("unknown scene \"" + std::string(name) + "\" (chainbench list shows them)");
  }
  const std::vector<SceneParam> params = all_params(*recipe);
  SceneParams values;
  for (const SceneParam& p : params)
    values.set(p.key, p.value);
  for (auto it = sets.begin(); it != sets.end(); ++it) {
    const std::string& kv = *it;
    const std::size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set " + cut_for_message(kv) + ": expected KEY=VALUE");
    const std::string key = kv.substr(0, eq);
    const std::string shown = cut_for_message(key);  // what a message may echo of it
    // One value per key, as in a scene file: a second one is a typo more often than an intent.
    const auto again = std::find_if(sets.begin(), it, [&](const std::string& earlier) {
      return earlier.compare(0, key.size() + 1, key + "=") == 0;
    });
    if (again != it) {
      throw InputError("--set " + shown + ": given twice (" + cut_for_message(*again) + ", then " +
                       cut_for_message(kv) + ")" + (key == "steps" ? "; --steps sets it too" : ""));
    }
    const auto p = std::find_if(params.begin(), params.end(),
                                [&](const SceneParam& q) { return q.key == key; });
    if (p == params.end()) {
      std::string keys;
      for (const SceneParam& q : params)
        keys += (keys.empty() ? "" : ", ") + q.key;
      throw InputError("--set " + shown + ": scene " + recipe->name + " has no parameter \"" +
                       shown + "\" (it has: " + keys + ")");
    }
    const double v = parse_number("--set " + shown, kv.substr(eq + 1));
    if (p->integer && v != std::floor(v))
      throw InputError("--set " + shown + ": must be a whole number, got " +
                       cut_for_message(kv.substr(eq + 1)));
    if (v < p->min || v > p->max) {
      throw InputError("--set " + shown + ": " + num(v) + " is out of range [" + num(p->min) +
                       ", " + num(p->max) + "] for scene " + recipe->name);
    }
    values.set(key, v);
  }
  if (const std::size_t n = recipe->body_count(values); n > limits::kMaxBodies) {
    throw InputError("scene " + recipe->name + " with these parameters would hold " +
                     std::to_string(n) + " bodies, more than the limit of " +
                     std::to_string(limits::kMaxBodies));
  }
  Scene scene = recipe->build(values);
  scene.description = recipe->description;
  scene.family = recipe->family;
  scene.steps = values.count("steps");
  scene.dt = values.get("dt");
  scene.friction = values.get("friction");
  scene.restitution = values.get("restitution");
  scene.rotation = values.count("rotation") != 0;
  if (const double offset = values.get("offset"); offset != 0.0) {
    for (SceneBody& b : scene.bodies)
      b.center.x += offset, b.center.y += offset;
    for (Expectation& e : scene.expect) {
      e.center.x += offset, e.center.y += offset;
      for (std::optional<double>* bound : {&e.min_x, &e.min_y, &e.max_x, &e.max_y}) {
        if (*bound) **bound += offset;
      }
    }
  }
  return scene;
}

namespace build {

void ground(Scene& s, double half_width, double top, double x, const std::string& name) {
  box(s, name, BodyKind::kStatic, {x, top - 1.0}, {half_width, 1.0});
}

std::size_t box(Scene& s, std::string name, BodyKind kind, Vec2d center, Vec2d half, double mass) {
  SceneBody b;
  b.name = std::move(name);
  b.kind = kind;
  b.center = center;
  b.half_extents = half;
  b.mass = kind == BodyKind::kDynamic ? mass : 0.0;
  s.bodies.push_back(std::move(b));
  return s.bodies.size() - 1;
}

std::string label(std::string_view prefix, int a) {
  std::string s(prefix);
  s.append(std::to_string(a));
  return s;
}

std::string label(std::string_view prefix, int a, int b) {
  std::string s = label(prefix, a);
  s.push_back('_');
  s.append(std::to_string(b));
  return s;
}

Expectation expect_center(std::size_t body, Vec2d center, double tolerance) {
  Expectation e;
  e.kind = Expectation::Kind::kCenter;
  e.body = body;
  e.center = center;
  e.tolerance = tolerance;
  return e;
}

Expectation expect_moved(std::size_t body, Vec2d moved, double tolerance) {
  Expectation e;
  e.kind = Expectation::Kind::kMoved;
  e.body = body;
  e.moved = moved;
  e.tolerance = tolerance;
  return e;
}

Expectation expect_bounds(std::size_t body, std::optional<double> min_x,
                          std::optional<double> min_y, std::optional<double> max_x,
                          std::optional<double> max_y) {
  Expectation e;
  e.kind = Expectation::Kind::kBounds;
  e.body = body;
  e.min_x = min_x, e.min_y = min_y, e.max_x = max_x, e.max_y = max_y;
  return e;
}

Expectation expect_no_overlap(double depth, std::optional<int> from_step) {
  Expectation e;
  e.kind = Expectation::Kind::kNoOverlap;
  e.depth = depth;
  e.from_step = from_step;
  return e;
}

void expect_at_rest_where_built(Scene& s) {
  double smallest = HUGE_VAL;
  for (const SceneBody& b : s.bodies) {
    if (b.kind == BodyKind::kDynamic)
      smallest = std::min({smallest, 2.0 * b.half_extents.x, 2.0 * b.half_extents.y});
  }
  if (smallest < HUGE_VAL)
    s.expect.push_back(expect_moved(kEvery, {0.0, 0.0}, kVisible * smallest));
}

double fallen(double g, double dt, int steps) {
  return g * dt * dt * steps * (steps + 1.0) / 2.0;
}

double driven_push_distance(double v, double pusher, double row, double dt, int steps) {
  const double r = row / (pusher + row);
  return v * dt * (steps - (row / pusher) * (1.0 - std::pow(r, steps)));
}

void expect_squeezed(Scene& s, std::size_t body, int axis, double low, double high, double size) {
  const double gap = std::max(high - low, 0.0);
  const double forced = 0.5 * std::max(size - gap, 0.0);
  s.penetration_tolerance = forced + kVisible * size;
  const double lo = std::min(low, high), hi = std::max(low, high);
  s.expect.push_back(axis == 0 ? expect_bounds(body, lo, std::nullopt, hi, std::nullopt)
                               : expect_bounds(body, std::nullopt, lo, std::nullopt, hi));
}

}  // namespace build
}  // namespace chainbench
