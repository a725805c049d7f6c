// SPDX-License-Identifier: MIT
// The built-in scenes: parametric recipes, each declaring only what it needs (no gravity in a
// top-down push, no friction where none matters, no rotation unless asked).
#pragma once

#include "model/scene.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace chainbench {

struct SceneParam {
  std::string key;
  double value;  // the default
  double min;
  double max;
  bool integer;
  std::string help;
};

// Parameter values, all within their declared ranges.
class SceneParams {
 public:
  double get(const std::string& key) const;
  int count(const std::string& key) const { return static_cast<int>(get(key)); }
  void set(const std::string& key, double v) { values_[key] = v; }

 private:
  std::map<std::string, double, std::less<>> values_;
};

struct SceneRecipe {
  std::string name;
  std::string family;  // stacking, pushing, level, moving, seed2014, stress
  std::string description;
  std::vector<SceneParam> params;  // the scene's own; every scene also takes all_params()'s
  Scene (*build)(const SceneParams&);
  std::size_t (*body_count)(const SceneParams&);  // checked against the limit before build
  int steps = 120;                                // default run length
};

const std::vector<SceneRecipe>& scene_library();
// The default suite: the built-in scenes scripts/run.sh runs and its report lists, in that order
// (`chainbench list --suite default` prints them). Every name is a recipe of scene_library().
const std::vector<std::string>& default_suite();
const SceneRecipe* find_recipe(std::string_view name);
// The recipe's own parameters, then steps, dt (1/60), friction (0), restitution (0), rotation
// (0) and offset (0: moves the whole scene that far along x and y), which every scene takes.
std::vector<SceneParam> all_params(const SceneRecipe& recipe);

// Builds scene `name` with `sets` ("key=value") applied. Unknown scenes and keys, values that are
// not numbers or fall outside their range are refused (InputError) before anything is built.
Scene make_scene(std::string_view name, const std::vector<std::string>& sets);

// Helpers for recipes.
namespace build {
// A static box whose top face is at y = top.
void ground(Scene& s, double half_width, double top = 0.0, double x = 0.0,
            const std::string& name = "ground");
std::size_t box(Scene& s, std::string name, BodyKind kind, Vec2d center, Vec2d half,
                double mass = 1.0);
// "box12", "p3_4_": a prefix and numbers joined by '_' (built without operator+ chains, which
// GCC 12 misreports under -Wrestrict at -O3).
std::string label(std::string_view prefix, int a);
std::string label(std::string_view prefix, int a, int b);

// What a recipe states as its right answer (scene.h, Expectation).
// The share of a box's size by which a result may differ before it is visibly wrong: the same 5%
// the default penetration tolerance allows.
inline constexpr double kVisible = 0.05;
inline constexpr std::size_t kEvery = Expectation::kEveryDynamic;
Expectation expect_center(std::size_t body, Vec2d center, double tolerance);
// The body (or kEvery) ends within `tolerance` of its start moved by `moved`.
Expectation expect_moved(std::size_t body, Vec2d moved, double tolerance);
Expectation expect_bounds(std::size_t body, std::optional<double> min_x,
                          std::optional<double> min_y, std::optional<double> max_x,
                          std::optional<double> max_y);
Expectation expect_no_overlap(double depth, std::optional<int> from_step = std::nullopt);
// Every dynamic body stays where it was built, within kVisible of the smallest dynamic box.
void expect_at_rest_where_built(Scene& s);

// How far a body falls from rest in `steps` steps of dt under gravity g, integrated as the engines
// do (velocity first, then position): g dt^2 steps (steps + 1) / 2.
double fallen(double g, double dt, int steps);

// How far a row of mass `row` moves when a body of mass `pusher` touching it has its velocity set
// to v at the start of each of `steps` steps of dt and every push shares momentum (perfectly
// inelastic): in step k both move at u_k = (pusher v + row u_{k-1}) / (pusher + row), so they
// travel v steps dt less a lag of v dt (row / pusher) (1 - r^steps), r = row / (pusher + row).
double driven_push_distance(double v, double pusher, double row, double dt, int steps);

// A box of size `size` along `axis` squeezed between an immovable face at `low` and one at
// `high` (high - low < size): no place is right for it, and the least-penetrating one centres it
// with each face (size - (high - low)) / 2 deep. States that its centre ends between the faces and
// sets the scene's penetration tolerance to that forced overlap plus kVisible of the box.
void expect_squeezed(Scene& s, std::size_t body, int axis, double low, double high, double size);
}  // namespace build

std::vector<SceneRecipe> stacking_scenes();
std::vector<SceneRecipe> pushing_scenes();
std::vector<SceneRecipe> seed2014_scenes();
std::vector<SceneRecipe> stress_scenes();
std::vector<SceneRecipe> level_scenes();
std::vector<SceneRecipe> moving_scenes();

}  // namespace chainbench
