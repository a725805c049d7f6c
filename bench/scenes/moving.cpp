// SPDX-License-Identifier: MIT
// Moving scenes: worlds in which every engine must work each step, for the benchmark's fair race
// (docs/benchmarks.md §3). Each repeats a small event across the scene, so that it scales with one
// size parameter and keeps its character, and states where every body is at the end, with the
// windowed facts that hold on the way. Unit boxes (1 kg) unless said; frictionless, upright and
// inelastic, as every built-in scene: with restitution 0 no contact ever speeds a body up along
// its normal, so speeds stay within the ones the scene starts with, plus gravity.
#include "scenes/portable_random.h"
#include "scenes/scene_library.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace chainbench {
namespace {

using build::box;
constexpr double kTolerance = build::kVisible;  // of a unit box: 5 cm
constexpr double kG = 10.0;

// A static box covering [x0, x1] x [y0, y1].
void wall(Scene& s, std::string name, double x0, double y0, double x1, double y1) {
  box(s, std::move(name), BodyKind::kStatic, {0.5 * (x0 + x1), 0.5 * (y0 + y1)},
      {0.5 * (x1 - x0), 0.5 * (y1 - y0)});
}

// Every state from the first on: the body's centre within [min, max] on the axes given.
Expectation always_within(std::size_t body, std::optional<double> min_x,
                          std::optional<double> min_y, std::optional<double> max_x,
                          std::optional<double> max_y) {
  Expectation e = build::expect_bounds(body, min_x, min_y, max_x, max_y);
  e.from_step = 0;
  return e;
}

// ---- rain ------------------------------------------------------------------------------------
// The scene model cannot create bodies while it runs, and under gravity alone drops waiting high
// up would land ever faster; without gravity a landed drop would float off on the slightest
// rebound an iterative solver leaves, and a driver holding a falling drop's velocity moves it by
// g dt^2 a step more in some engines than in others. So every drop waits, at rest under gravity,
// on a thin static shelf beside its column, and a driver that holds only its horizontal velocity
// slides it off the shelf over the column (1.1 m at `speed`, then held at x), where gravity drops
// it a few centimetres onto the column's top, as a walking character falls off a ledge. It stops
// there (restitution 0, and the column rests on the ground) and is the top the next drop lands
// on. Column c takes a drop every `period` steps, from a phase of its own, so that about
// cols / period drops land per step across the scene. Nothing is held along gravity's axis, so
// every engine is asked the same thing, and the answer is exact but for the step or two by which
// engines differ in when a corner stops holding a box up (level.cpp, ledge_walk). Each drop falls
// 4 cm more than the one before it (its shelf and the room under the next); over the default 120
// steps that stays under 0.25 m, where Box2D and Chipmunk take the blows within 5 cm; over 300
// steps Box2D lets a drop sink just past that into a column of ten.
struct RainPlan {
  int cols = 0, period = 0, steps = 0, slide = 0;  // slide: steps a drop takes to cross kSlide
  double dt = 0.0;
  std::vector<int> height;  // pile boxes of each column, 1 to 2 depth - 1
  std::vector<int> phase;   // step of each column's first slide, 0 to period - 1
  static constexpr double kShelf = 0.02, kClear = 0.02, kGap = 0.04;  // m
  static constexpr double kSlide = 1.1;  // m, from the middle of the shelf to the column's
  // Drops of column c: every one that slides before the end, and the one waiting then.
  int drops(int c) const { return (steps - phase[c] + period - 1) / period + 1; }
  // Drop k falls from kGap above the column, plus the shelves and clearances under it.
  double fall(int k) const { return kGap + k * (kShelf + kClear); }
  // Steps from leaving the shelf to resting on the column: the fall's, and two for the engines.
  int fall_steps(int k) const {
    return static_cast<int>(std::ceil(std::sqrt(2.0 * fall(k) / kG) / dt)) + 2;
  }
};

RainPlan rain_plan(const SceneParams& p) {
  RainPlan plan;
  plan.cols = p.count("cols"), plan.steps = p.count("steps"), plan.dt = p.get("dt");
  plan.slide =
      std::max(1, static_cast<int>(std::ceil(RainPlan::kSlide / (p.get("speed") * plan.dt))));
  PortableRandom rng(7);
  const int spread = 2 * p.count("depth") - 1;
  plan.height.resize(static_cast<std::size_t>(plan.cols));
  for (int& h : plan.height)
    h = 1 + std::min(spread - 1, static_cast<int>(rng.uniform(0.0, spread)));
  // A drop lands before the next one leaves its shelf: no drop falls on one still falling.
  const int period = p.count("period");
  plan.period = std::max(period, plan.fall_steps((plan.steps + period - 1) / period + 1) + 1);
  // Phases spread evenly over the period, dealt to the columns in shuffled order.
  std::vector<int> order(static_cast<std::size_t>(plan.cols));
  std::iota(order.begin(), order.end(), 0);
  for (std::size_t i = order.size(); i > 1; --i)
    std::swap(order[i - 1], order[static_cast<std::size_t>(rng.next() % i)]);
  plan.phase.resize(order.size());
  for (std::size_t c = 0; c < order.size(); ++c) {
    plan.phase[c] = static_cast<int>(static_cast<long long>(order[c]) * plan.period / plan.cols);
  }
  return plan;
}

// Drop k of a column whose centre is at x and whose pile is `pile` boxes tall, and its shelf. The
// shelf ends 0.1 m short of the column, so that a drop slid over the column is well off it: a
// box exactly at a shelf's edge is held up by one engine's skin and not by another's.
void rain_drop(Scene& s, const RainPlan& plan, int c, int k, double x, int pile) {
  const double landed = pile + k + 0.5;  // on the column's k-th drop
  const double shelf_top = pile + k + plan.fall(k);
  wall(s, build::label("shelf", c, k), x - 1.6, shelf_top - RainPlan::kShelf, x - 0.6, shelf_top);
  const double x0 = x - RainPlan::kSlide, y0 = shelf_top + 0.5;
  const std::size_t b =
      box(s, build::label("drop", c, k), BodyKind::kDynamic, {x0, y0}, {0.5, 0.5});
  const int start = plan.phase[c] + k * plan.period, over = start + plan.slide;
  Driver slide{b, {RainPlan::kSlide / (plan.slide * plan.dt), 0.0}, start, over, true, false};
  Driver hold{b, {0.0, 0.0}, over, limits::kMaxSteps, true, false};
  s.drivers.push_back(slide);
  s.drivers.push_back(hold);
  // Off its shelf onto its column, never into it, never up.
  s.expect.push_back(
      always_within(b, x0 - kTolerance, landed - kTolerance, x + kTolerance, y0 + kTolerance));
  const int n = plan.steps;
  if (n <= over) {  // waiting or sliding: where the driver took it, falling once off the shelf
    const double moved = n <= start ? 0.0 : RainPlan::kSlide * (n - start) / plan.slide;
    // Off the shelf once its centre is within 0.1 m of the column's, give or take a step.
    const int off =
        start +
        static_cast<int>(std::floor((RainPlan::kSlide - 0.1) * plan.slide / RainPlan::kSlide));
    const double drop = build::fallen(kG, plan.dt, std::max(0, n - off + 2));
    s.expect.push_back(build::expect_bounds(b, x0 + moved - kTolerance, y0 - drop - kTolerance,
                                            x0 + moved + kTolerance, y0 + kTolerance));
  } else if (n >= over + plan.fall_steps(k)) {  // landed
    s.expect.push_back(build::expect_center(b, {x, landed}, kTolerance));
  } else {  // falling
    s.expect.push_back(build::expect_bounds(b, x - kTolerance, landed - kTolerance, x + kTolerance,
                                            y0 + kTolerance));
  }
}

Scene rain(const SceneParams& p) {
  Scene s;
  s.name = "rain";
  const RainPlan plan = rain_plan(p);
  constexpr double kPitch = 2.5;  // a column, and room beside it for its shelves
  const double half_width = 0.5 * kPitch * plan.cols;
  double tallest = 0.0;
  for (int c = 0; c < plan.cols; ++c)
    tallest = std::max(tallest, plan.height[c] + plan.drops(c) + plan.fall(plan.drops(c)));
  build::ground(s, half_width + 1.0);
  wall(s, "wall_left", -half_width - 1.0, 0.0, -half_width, tallest + 2.0);
  wall(s, "wall_right", half_width, 0.0, half_width + 1.0, tallest + 2.0);
  for (int c = 0; c < plan.cols; ++c) {
    const double x = kPitch * (c - 0.5 * (plan.cols - 1)) + 0.5;
    for (int k = 0; k < plan.height[c]; ++k) {
      const std::size_t b =
          box(s, build::label("pile", c, k), BodyKind::kDynamic, {x, 0.5 + k}, {0.5, 0.5});
      // The pile stands on the ground throughout: a drop's blow goes into the ground.
      Expectation still = build::expect_moved(b, {0.0, 0.0}, kTolerance);
      still.from_step = 0;
      s.expect.push_back(still);
    }
    for (int k = 0; k < plan.drops(c); ++k)
      rain_drop(s, plan, c, k, x, plan.height[c]);
  }
  return s;
}

std::size_t rain_count(const SceneParams& p) {
  const RainPlan plan = rain_plan(p);
  std::size_t n = 3;
  for (int c = 0; c < plan.cols; ++c)
    n += static_cast<std::size_t>(plan.height[c] + 2 * plan.drops(c));
  return n;
}

// ---- smash -----------------------------------------------------------------------------------
// Lanes, each a closed container holding a heavy block, 2 m wide and as tall as the wall, thrown
// along the floor at `speed` into `cols` columns of `height` unit boxes that stand `gap` apart,
// the block `heavy` times the mass of all of them. Frictionless and inelastic, the block sweeps
// the columns up one by one: each it meets joins the train in front of it, and the train shares
// its momentum, so after k columns it moves at V_k = M v / (M + k m), m a column's mass. Every
// box is hit face on by the one before it in its row and moves with its column: no box slides
// over another. (Over a block lower than the wall the rows above it would slide across the
// flush tops of moving boxes, where Box2D and Chipmunk catch a box at a seam and carry it off:
// the scene would measure that instead of the smash.) The train stops against the far wall, the
// container being long enough for it to gather every column first; the default 120 steps end
// before that. Box2D and Chipmunk share a blow along a train unevenly, the front column moving
// off a little faster than the rest: within kVisible over 120 steps, beyond it over 180, and at
// the far wall their trains spring back where a rigid, inelastic one stops.
//
// Engines take each collision at the end of a step, up to one step late, moving the train on at
// the speed before it for that long: each collision can put it up to (V_(k-1) - V_k) dt ahead,
// and those add up to at most (v - V_k) dt, which the tolerance allows beside kVisible.
struct SmashLane {
  int cols, height;
  double gap, v, heavy, dt;
  double column_mass() const { return height; }
  double block_mass() const { return heavy * cols * column_mass(); }
  double speed(int k) const { return v * block_mass() / (block_mass() + k * column_mass()); }
  double length() const { return 3.5 + cols * (1.0 + gap) + 2.0; }     // inside the container
  double column_left(int j) const { return 2.5 + (j + 1) * gap + j; }  // column j, from 0
  // Where the block's face is t seconds after the throw, and how many columns it has gathered.
  std::pair<double, int> front(double t) const {
    double f = 2.5;
    for (int k = 0; k < cols; ++k) {
      const double next = 2.5 + (k + 1) * gap;  // the face when the train meets column k
      const double reach = (next - f) / speed(k);
      if (t < reach) return {f + speed(k) * t, k};
      t -= reach, f = next;
    }
    return {std::min(f + speed(cols) * t, length() - cols), cols};
  }
};

void smash_lane(Scene& s, const SmashLane& lane, int index, Vec2d o, int steps) {
  const double L = lane.length(), top = lane.height + 1.0, h = lane.height;
  const std::string prefix = build::label("lane", index) + "_";
  wall(s, prefix + "floor", o.x - 1.0, o.y - 1.0, o.x + L + 1.0, o.y);
  wall(s, prefix + "ceiling", o.x - 1.0, o.y + top, o.x + L + 1.0, o.y + top + 1.0);
  wall(s, prefix + "left", o.x - 1.0, o.y, o.x, o.y + top);
  wall(s, prefix + "right", o.x + L, o.y, o.x + L + 1.0, o.y + top);
  const auto [face, gathered] = lane.front(lane.dt * steps);
  const double tolerance = kTolerance + (lane.v - lane.speed(gathered)) * lane.dt;

  const std::size_t block = box(s, prefix + "block", BodyKind::kDynamic, {o.x + 1.5, o.y + 0.5 * h},
                                {1.0, 0.5 * h}, lane.block_mass());
  s.bodies[block].velocity = {lane.v, 0.0};
  s.expect.push_back(build::expect_center(block, {o.x + face - 1.0, o.y + 0.5 * h}, tolerance));
  // On the way: never back, never off the floor or up.
  s.expect.push_back(always_within(block, o.x + 1.5 - kTolerance, o.y + 0.5 * h - kTolerance,
                                   std::nullopt, o.y + 0.5 * h + kTolerance));
  for (int j = 0; j < lane.cols; ++j) {
    const double x = o.x + lane.column_left(j) + 0.5;
    const double end_x = j < gathered ? o.x + face + j + 0.5 : x;
    for (int r = 0; r < lane.height; ++r) {
      const double y = o.y + 0.5 + r;
      const std::size_t b =
          box(s, prefix + build::label("box", j, r), BodyKind::kDynamic, {x, y}, {0.5, 0.5});
      s.expect.push_back(build::expect_center(b, {end_x, y}, tolerance));
      s.expect.push_back(
          always_within(b, x - kTolerance, y - kTolerance, std::nullopt, y + kTolerance));
    }
  }
}

SmashLane smash_lane_of(const SceneParams& p) {
  return {p.count("cols"), p.count("height"), p.get("gap"),
          p.get("speed"),  p.get("heavy"),    p.get("dt")};
}

Scene smash(const SceneParams& p) {
  Scene s;
  s.name = "smash";
  const SmashLane lane = smash_lane_of(p);
  const int lanes = p.count("lanes");
  // Lanes on a grid about as tall as it is wide, 1 m apart.
  const double w = lane.length() + 3.0, h = lane.height + 4.0;
  const int across = std::max(1, static_cast<int>(std::lround(std::sqrt(lanes * h / w))));
  for (int i = 0; i < lanes; ++i)
    smash_lane(s, lane, i, {w * (i % across), h * (i / across)}, p.count("steps"));
  return s;
}

std::size_t smash_count(const SceneParams& p) {
  return static_cast<std::size_t>(p.count("lanes")) *
         (5u + static_cast<std::size_t>(p.count("cols")) * p.count("height"));
}

// ---- bulldozer -------------------------------------------------------------------------------
// Top-down (no gravity): lanes of `rows` rows of crates, each lane swept by a kinematic blade
// 1 m thick moving at `speed` along +x, with a row outside every blade's span between lanes.
// Rows are 0.25 m apart and never touch, and crates in a row lie 0.5 to 1.5 times `spacing`
// apart. A blade's face meets its rows' crates in turn; each it meets joins the packed train in
// front of it at the blade's speed (a kinematic body is not slowed). So at the end every crate a
// blade reached is packed ahead of it, in its row, in the order it stood, and every other crate
// is where it stood: none behind a blade inside its span, none moved outside it. Box2D and
// Chipmunk pack a long train loosely (Box2D's front crates run ahead of the blade, Box2D without
// warm starting squeezes the train shorter instead), by more than kVisible once a train is
// longer than a few crates: the default spacing and run keep trains to one or two, where both
// stay within 3 cm (at 33,000 bodies: the worst of many rows).
Scene bulldozer(const SceneParams& p) {
  Scene s;
  s.name = "bulldozer";
  s.gravity = {0.0, 0.0};
  const int lanes = p.count("lanes"), rows = p.count("rows"), crates = p.count("crates");
  const double v = p.get("speed"), t = p.get("dt") * p.count("steps"), front = v * t;
  constexpr double kPitch = 1.25;
  PortableRandom rng(11);
  const int total_rows = lanes * (rows + 1) + 1;  // a free row below each lane, one above all
  double far = 0.0;
  std::vector<std::vector<double>> row_x(static_cast<std::size_t>(total_rows));
  for (std::vector<double>& xs : row_x) {
    double right = 0.0;  // the blades' faces start at x = 0
    for (int k = 0; k < crates; ++k) {
      right += rng.uniform(0.5, 1.5) * p.get("spacing") + 1.0;
      xs.push_back(right - 0.5);
    }
    far = std::max(far, right);
  }
  // A closed yard, its far wall beyond anything a blade can push in the run.
  const double top = kPitch * (total_rows - 1) + 1.0;
  wall(s, "yard_bottom", -3.0, -2.0, far + front + 2.0, -1.0);
  wall(s, "yard_top", -3.0, top, far + front + 2.0, top + 1.0);
  wall(s, "yard_back", -3.0, -1.0, -2.0, top);
  wall(s, "yard_far", far + front + 1.0, -1.0, far + front + 2.0, top);
  for (int l = 0; l < lanes; ++l) {
    const double y0 = kPitch * (l * (rows + 1) + 1), y1 = y0 + kPitch * (rows - 1);
    const std::size_t blade = box(s, build::label("blade", l), BodyKind::kKinematic,
                                  {-0.5, 0.5 * (y0 + y1)}, {0.5, 0.5 * (y1 - y0) + 0.625});
    s.bodies[blade].velocity = {v, 0.0};
  }
  for (int g = 0; g < total_rows; ++g) {
    const bool swept = g % (rows + 1) != 0;
    const double y = kPitch * g;
    int packed = 0;  // crates of this row the blade has met
    for (std::size_t k = 0; k < row_x[static_cast<std::size_t>(g)].size(); ++k) {
      const double x = row_x[static_cast<std::size_t>(g)][k];
      const std::size_t b = box(s, build::label("crate", g, static_cast<int>(k)),
                                BodyKind::kDynamic, {x, y}, {0.5, 0.5});
      if (!swept) {
        Expectation still = build::expect_moved(b, {0.0, 0.0}, kTolerance);
        still.from_step = 0;
        s.expect.push_back(still);
        continue;
      }
      // Met when the train's front, the blade's face plus the crates already packed, reaches
      // the crate's back face.
      const bool met = front + packed >= x - 0.5;
      const double end_x = met ? front + packed + 0.5 : x;
      packed += met ? 1 : 0;
      s.expect.push_back(
          always_within(b, x - kTolerance, y - kTolerance, std::nullopt, y + kTolerance));
      s.expect.push_back(build::expect_center(b, {end_x, y}, kTolerance));
    }
  }
  return s;
}

std::size_t bulldozer_count(const SceneParams& p) {
  const auto lanes = static_cast<std::size_t>(p.count("lanes"));
  const auto rows = lanes * (static_cast<std::size_t>(p.count("rows")) + 1) + 1;
  return 4 + lanes + rows * static_cast<std::size_t>(p.count("crates"));
}

}  // namespace

SceneRecipe spawn_rain_recipe();  // spawn_rain.cpp
SceneRecipe churn_recipe();       // churn.cpp

std::vector<SceneRecipe> moving_scenes() {
  return {
      {"rain",
       "moving",
       "boxes slid off shelves onto the columns of a pile below, about cols / period landing per "
       "step",
       {{"cols", 200, 1, 1000000, true, "pile columns"},
        {"depth", 4, 1, 1000, true, "mean pile boxes per column"},
        {"period", 40, 1, 1000000, true, "steps between landings on one column"},
        {"speed", 2, 0.01, 100, false, "sliding speed off the shelf, m/s"}},
       rain,
       rain_count,
       120},
      {"smash",
       "moving",
       "lanes, each a heavy block thrown into a row of stacked columns inside a container",
       {{"lanes", 4, 1, 1000000, true, "containers"},
        {"cols", 6, 1, 1000, true, "columns in each lane"},
        {"height", 6, 1, 1000, true, "boxes in each column (and the block's height, m)"},
        {"gap", 1, 0, 100, false, "between columns, m"},
        {"speed", 4, 0.01, 100, false, "throw speed, m/s"},
        {"heavy", 1, 0.01, 1e6, false, "block mass / mass of all the columns"}},
       smash,
       smash_count,
       120},
      {"bulldozer",
       "moving",
       "top-down: kinematic blades pushed through a field of crates",
       {{"lanes", 4, 1, 1000000, true, "blades"},
        {"rows", 8, 1, 10000, true, "rows of crates each blade sweeps"},
        {"crates", 6, 1, 100000, true, "crates in each row"},
        {"spacing", 2.5, 0.01, 1000, false,
         "mean gap between crates in a row, m (0.5 to 1.5 times it)"},
        {"speed", 2, 0.01, 100, false, "blade speed, m/s"}},
       bulldozer,
       bulldozer_count,
       120},
      spawn_rain_recipe(),
      churn_recipe(),
  };
}

}  // namespace chainbench
