// The built-in scenes: parametric recipes, each declaring only what it needs (no gravity in a
// top-down push, no friction where none matters, no rotation unless asked).
#pragma once

#include "scene.h"

#include <map>
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
  std::string family;  // stacking, pushing, seed2014, stress
  std::string description;
  std::vector<SceneParam> params;  // the scene's own; every scene also takes all_params()'s
  Scene (*build)(const SceneParams&);
  std::size_t (*body_count)(const SceneParams&);  // checked against the limit before build
  int steps = 120;                                // default run length
};

const std::vector<SceneRecipe>& scene_library();
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
}  // namespace build

std::vector<SceneRecipe> stacking_scenes();
std::vector<SceneRecipe> pushing_scenes();
std::vector<SceneRecipe> seed2014_scenes();
std::vector<SceneRecipe> stress_scenes();

}  // namespace chainbench
