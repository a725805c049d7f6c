// SPDX-License-Identifier: MIT
#include "benchmarks/families.h"

#include "scenes/scene_library.h"

#include <string>
#include <tuple>
#include <utility>

namespace chainbench {

const std::vector<Family>& benchmark_families() {
  // random_pile is a deep pile (2 sqrt(n) m wide) that the reference engines' default solvers
  // let sink; shallow_pile, five boxes deep with friction, is one they hold, so that there every
  // engine does the same work. The scaling series run the engine under test from about 5k bodies
  // to as many as a step takes well under a second; the others stop at the sizes docs/results.md
  // has them at, or where a step takes seconds. Worlds that come to rest are warmed up for 45
  // steps or more: the reference engines put a body to sleep after half a second (30 steps) at
  // rest, and their sleeping rows should time the world they sleep in. The moving scenes are timed
  // over steps 60 to 120 of their own 120-step run, which their right answers are stated for: the
  // rain is falling, the blocks are gathering columns and the blades are pushing trains of crates
  // throughout.
  static const std::vector<Family> families = [] {
    std::vector<Family> f;
    f.push_back({"stack", "stack", {}, {0}, {}, 120});
    f.push_back({"pyramid", "pyramid", {"base"}, {20, 100}, {}, 60});
    Family pyramids{"many_pyramids", "many_pyramids", {"rows", "cols"}, {10, 20, 50, 100}, {}, 45};
    pyramids.scaling_base = 10;  // 5,510 bodies
    pyramids.others_max = 25'000;
    f.push_back(pyramids);
    Family row{"push_row", "push_row", {"n"}, {100, 10'000, 100'000}, {}, 30};
    row.scaling_base = 10'000;
    f.push_back(row);
    Family pile{"random_pile", "random_pile", {"n"}, {1'000, 10'000, 100'000, 1'000'000}, {}, 30};
    pile.scaling_base = 10'000;
    f.push_back(pile);
    f.push_back({"shallow_pile", "random_pile", {"n"}, {10'000}, {"layers=5", "friction=0.5"}, 45});
    Family wall{"stack_wall", "stack_wall", {"cols"}, {500, 5'000, 50'000, 100'000}, {}, 45};
    wall.scaling_base = 500;  // 5,001 bodies
    wall.others_max = 60'000;
    f.push_back(wall);
    for (auto [name, key, small, large] :
         {std::tuple{"rain", "cols", 1'000, 10'000}, std::tuple{"smash", "lanes", 250, 2'500},
          std::tuple{"bulldozer", "lanes", 180, 1'800}}) {
      Family moving{name, name, {key}, {small, large}, {}, 60};
      moving.window = 60;
      moving.moving = true;
      moving.others_max = 20'000;
      f.push_back(moving);
    }
    // Bodies that come and go: warmed up until `waves` waves are in (25 waves of 4 x cols boxes,
    // one every 4 steps: 10,000 boxes at cols=100), then timed over 60 steps in which 15 waves
    // enter and 15 leave.
    Family spawn{
        "spawn_rain", "spawn_rain", {"cols"}, {100, 1'000}, {"waves=25", "period=4", "height=4"},
        100};
    spawn.window = 60;
    spawn.moving = true;
    spawn.others_max = 20'000;
    f.push_back(spawn);
    // One body created and one destroyed a step in a wall at rest, against the same wall with
    // nothing coming or going (churn_base): what a game's projectiles cost beyond their physics.
    for (auto [name, per_step] : {std::pair{"churn", 1}, std::pair{"churn_base", 0}}) {
      Family churn{
          name, "churn", {"cols"}, {1'000, 10'000}, {"per_step=" + std::to_string(per_step)}, 45};
      churn.window = 60;
      churn.others_max = 20'000;
      f.push_back(churn);
    }
    return f;
  }();
  return families;
}

std::vector<std::string> family_sets(const Family& family, int size) {
  std::vector<std::string> sets = family.sets;
  for (const std::string& key : family.size_keys)
    sets.push_back(key + "=" + std::to_string(size));
  // A moving scene is built for its window, a resting one for longer than any benchmark runs
  // (drivers and expectation windows must outlast it).
  const int steps = family.window > 0 ? family.warmup + family.window : 10'000'000;
  sets.push_back("steps=" + std::to_string(steps));
  return sets;
}

std::size_t family_bodies(const Family& family, int size) {
  const SceneRecipe& recipe = *find_recipe(family.scene);
  SceneParams params;
  for (const SceneParam& p : all_params(recipe))
    params.set(p.key, p.value);
  for (const std::string& set : family_sets(family, size)) {
    const std::size_t eq = set.find('=');
    params.set(set.substr(0, eq), std::stod(set.substr(eq + 1)));
  }
  return recipe.body_count(params);
}

}  // namespace chainbench
