// SPDX-License-Identifier: MIT
// Stacking scenes: boxes resting on boxes under gravity.
#include "scenes/portable_random.h"
#include "scenes/scene_library.h"

#include <algorithm>
#include <cmath>

namespace chainbench {
namespace {

using build::box;
using build::ground;

std::size_t triangle(int base) {
  return static_cast<std::size_t>(base) * static_cast<std::size_t>(base + 1) / 2;
}

Scene stack(const SceneParams& p) {
  Scene s;
  s.name = "stack";
  const double h = 0.5 * p.get("size");
  ground(s, std::max(10.0, 10.0 * h));
  for (int i = 0; i < p.count("n"); ++i) {
    box(s, build::label("box", i), BodyKind::kDynamic, {0.0, h + 2.0 * h * i}, {h, h}, 4.0 * h * h);
  }
  build::expect_at_rest_where_built(s);  // built at rest, box on box: nothing moves
  return s;
}

// Rows of touching boxes, each row centred on the one below: the layout 2D engine benchmarks call
// the large pyramid.
void add_pyramid(Scene& s, const std::string& prefix, int base, double size, double x0, double y0) {
  const double h = 0.5 * size;
  for (int row = 0; row < base; ++row) {
    for (int k = 0; k < base - row; ++k) {
      const double x = x0 + size * (k - 0.5 * (base - row - 1));
      box(s, build::label(prefix, row, k), BodyKind::kDynamic, {x, y0 + h + size * row}, {h, h},
          size * size);
    }
  }
}

Scene pyramid(const SceneParams& p) {
  Scene s;
  s.name = "pyramid";
  const int base = p.count("base");
  const double size = p.get("size");
  ground(s, size * base + 2.0);
  add_pyramid(s, "b", base, size, 0.0, 0.0);
  build::expect_at_rest_where_built(s);
  return s;
}

Scene many_pyramids(const SceneParams& p) {
  Scene s;
  s.name = "many_pyramids";
  const int rows = p.count("rows"), cols = p.count("cols"), base = p.count("base");
  const double pitch = base + 2.0;  // room between neighbouring pyramids, and above each shelf
  const double width = cols * pitch;
  for (int r = 0; r < rows; ++r) {
    const double top = r * (pitch + 1.0);
    ground(s, 0.5 * width + 1.0, top, 0.0, build::label("shelf", r));
    for (int c = 0; c < cols; ++c) {
      add_pyramid(s, build::label("p", r, c) + "_", base, 1.0, -0.5 * width + pitch * (c + 0.5),
                  top);
    }
  }
  build::expect_at_rest_where_built(s);
  return s;
}

// A wall of `cols` touching columns, each `height` unit boxes tall: many short stacks side by
// side, the layout that scales a stack to any number of bodies without making it taller.
Scene stack_wall(const SceneParams& p) {
  Scene s;
  s.name = "stack_wall";
  const int cols = p.count("cols"), height = p.count("height");
  ground(s, 0.5 * cols + 2.0);
  for (int c = 0; c < cols; ++c) {
    for (int r = 0; r < height; ++r) {
      box(s, build::label("b", c, r), BodyKind::kDynamic, {c - 0.5 * (cols - 1), 0.5 + r},
          {0.5, 0.5});
    }
  }
  build::expect_at_rest_where_built(s);  // upright boxes on horizontal faces: nothing moves
  return s;
}

Scene mass_ratio_stack(const SceneParams& p) {
  Scene s;
  s.name = "mass_ratio_stack";
  ground(s, 10.0);
  const int n = p.count("n");
  for (int i = 0; i < n; ++i) {
    box(s, build::label("box", i), BodyKind::kDynamic, {0.0, 0.5 + i}, {0.5, 0.5},
        i == n - 1 ? p.get("ratio") : 1.0);
  }
  build::expect_at_rest_where_built(s);  // whatever the top weighs, rigid boxes do not give way
  return s;
}

Scene heavy_on_light(const SceneParams& p) {
  Scene s;
  s.name = "heavy_on_light";
  const double size = p.get("size");
  ground(s, size + 10.0);
  // The light boxes sit under the heavy box's edges, side by side at least.
  const double x = std::max(0.5 * size - 0.5, 0.5);
  const std::size_t left = box(s, "light_left", BodyKind::kDynamic, {-x, 0.5}, {0.5, 0.5}, 1.0);
  const std::size_t right = box(s, "light_right", BodyKind::kDynamic, {x, 0.5}, {0.5, 0.5}, 1.0);
  const std::size_t heavy =
      box(s, "heavy", BodyKind::kDynamic, {0.0, 1.0 + p.get("drop") + 0.5 * size},
          {0.5 * size, 0.5 * size}, p.get("ratio"));
  // Frictionless and upright, the heavy box falls straight down and rests on the light ones, which
  // the floor holds where they are: its height is set by theirs, so it is judged by their size.
  const double rest = 1.0 + 0.5 * size;
  const double falling =
      s.bodies[heavy].center.y - build::fallen(-s.gravity.y, p.get("dt"), p.count("steps"));
  s.expect.push_back(build::expect_moved(left, {0.0, 0.0}, build::kVisible));
  s.expect.push_back(build::expect_moved(right, {0.0, 0.0}, build::kVisible));
  s.expect.push_back(build::expect_center(heavy, {0.0, std::max(rest, falling)}, build::kVisible));
  return s;
}

Scene overlap_recovery(const SceneParams& p) {
  Scene s;
  s.name = "overlap_recovery";
  const int base = p.count("base");
  const double pitch = 1.0 - p.get("overlap");  // centres closer than a box: every pair overlaps
  ground(s, base + 10.0);
  for (int row = 0; row < base; ++row) {
    for (int k = 0; k < base - row; ++k) {
      box(s, build::label("b", row, k), BodyKind::kDynamic,
          {pitch * (k - 0.5 * (base - row - 1)), 0.5 + pitch * row}, {0.5, 0.5});
    }
  }
  // Where each box ends is not unique, but by half the run every overlap is gone and no box is
  // pushed into the floor.
  if (p.count("steps") >= 2) {
    s.expect.push_back(build::expect_no_overlap(build::kVisible, p.count("steps") / 2));
  }
  Expectation above = build::expect_bounds(build::kEvery, std::nullopt, 0.5 - build::kVisible,
                                           std::nullopt, std::nullopt);
  above.from_step = 0;
  s.expect.push_back(above);
  return s;
}

// Boxes of mixed sizes dropped one by one into a container twice as wide as the pile ends up
// deep, each onto the highest box under it: a height map of 1 cm columns remembers, for every
// column, the top of the highest box that reaches into it and which box that is. A box never
// starts inside another (its base is the highest top any of its columns holds), and it is kept
// only where the box it rests on lies under at least 10 cm of it; otherwise another x is drawn.
// (Minimum-axis push-out slides a box that rests on a sliver of a corner off it, as a
// frictionless box would, into the void below.) The pile starts at rest, box on box, with the
// gaps and overhangs a real drop leaves.
Scene random_pile(const SceneParams& p) {
  Scene s;
  s.name = "random_pile";
  const int n = p.count("n");
  PortableRandom rng(static_cast<std::uint64_t>(p.count("seed")) * 7919u + 17u);
  // A box is 1 m^2 and 1 m tall on average, so `layers` deep means about n / layers metres wide.
  const double width =
      std::max(10.0, p.get("layers") > 0.0 ? static_cast<double>(n) / p.get("layers")
                                           : 2.0 * std::sqrt(static_cast<double>(n)));
  // 1 cm columns, coarser in a container so wide that they would not fit in a few megabytes.
  const double kColumn = std::max(0.01, width / 1e6);
  constexpr double kMinSupport = 0.1;
  constexpr int kTries = 16;
  const auto columns = static_cast<std::size_t>(std::ceil(width / kColumn)) + 1;
  std::vector<double> skyline(columns, 0.0);
  std::vector<std::int32_t> owner(columns, -1);  // box whose top the column holds, -1: ground
  auto column = [&](double x) {
    return static_cast<std::size_t>(std::floor((x + 0.5 * width) / kColumn));
  };
  std::vector<SceneBody> boxes;
  boxes.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double hx = rng.uniform(0.3, 0.7), hy = rng.uniform(0.3, 0.7);
    double x = 0.0, base = 0.0;
    std::size_t c0 = 0, c1 = 0;
    for (int attempt = 0; attempt < kTries; ++attempt) {
      x = rng.uniform(-0.5 * width + hx, 0.5 * width - hx);
      c0 = column(x - hx);
      c1 = std::min(columns - 1, column(x + hx));
      base = *std::max_element(skyline.begin() + static_cast<std::ptrdiff_t>(c0),
                               skyline.begin() + static_cast<std::ptrdiff_t>(c1) + 1);
      bool supported = base == 0.0;  // the ground supports everything
      for (std::size_t c = c0; c <= c1 && !supported; ++c) {
        if (skyline[c] != base || owner[c] < 0) continue;
        const SceneBody& below = boxes[static_cast<std::size_t>(owner[c])];
        const double shared = std::min(x + hx, below.center.x + below.half_extents.x) -
                              std::max(x - hx, below.center.x - below.half_extents.x);
        supported = shared >= kMinSupport;
      }
      if (supported) break;
    }
    for (std::size_t c = c0; c <= c1; ++c) {
      skyline[c] = base + 2.0 * hy;
      owner[c] = i;
    }
    SceneBody b;
    b.name = build::label("box", i);
    b.center = {x, base + hy};
    b.half_extents = {hx, hy};
    b.mass = 4.0 * hx * hy;
    boxes.push_back(std::move(b));
  }
  const double height = *std::max_element(skyline.begin(), skyline.end()) + 5.0;
  ground(s, 0.5 * width + 1.0);
  box(s, "wall_left", BodyKind::kStatic, {-0.5 * width - 0.5, 0.5 * height}, {0.5, 0.5 * height});
  box(s, "wall_right", BodyKind::kStatic, {0.5 * width + 0.5, 0.5 * height}, {0.5, 0.5 * height});
  for (SceneBody& b : boxes)
    s.bodies.push_back(std::move(b));
  // Upright boxes on horizontal faces: every contact pushes straight up, so even without friction
  // the pile is in equilibrium and stays as it was dropped.
  build::expect_at_rest_where_built(s);
  return s;
}

}  // namespace

std::vector<SceneRecipe> stacking_scenes() {
  return {
      {"stack",
       "stacking",
       "a vertical stack of n boxes on the ground",
       {{"n", 15, 1, 2000, true, "boxes"}, {"size", 1.0, 0.01, 100.0, false, "box edge, m"}},
       stack,
       [](const SceneParams& p) { return static_cast<std::size_t>(p.count("n")) + 1; },
       600},
      {"pyramid",
       "stacking",
       "a pyramid of touching boxes; base=100 is the 5,050-box large pyramid engine benchmarks use",
       {{"base", 20, 1, 2000, true, "boxes in the bottom row"},
        {"size", 1.0, 0.01, 100.0, false, "box edge, m"}},
       pyramid,
       [](const SceneParams& p) { return triangle(p.count("base")) + 1; },
       300},
      {"many_pyramids",
       "stacking",
       "rows x cols pyramids, each row on its own shelf (20 x 20 x base 10 = 22,000 boxes)",
       {{"rows", 20, 1, 200, true, "shelves"},
        {"cols", 20, 1, 200, true, "pyramids per shelf"},
        {"base", 10, 1, 100, true, "boxes in each bottom row"}},
       many_pyramids,
       [](const SceneParams& p) {
         return static_cast<std::size_t>(p.count("rows")) *
                (p.count("cols") * triangle(p.count("base")) + 1);
       },
       120},
      {"stack_wall",
       "stacking",
       "a wall of cols touching columns, each height boxes tall",
       {{"cols", 100, 1, 1000000, true, "columns"}, {"height", 10, 1, 1000, true, "boxes each"}},
       stack_wall,
       [](const SceneParams& p) {
         return static_cast<std::size_t>(p.count("cols")) * p.count("height") + 1;
       },
       300},
      {"mass_ratio_stack",
       "stacking",
       "n unit boxes, the top one ratio times heavier than the others",
       {{"n", 5, 2, 1000, true, "boxes"},
        {"ratio", 100, 1e-6, 1e6, false, "top mass / other mass"}},
       mass_ratio_stack,
       [](const SceneParams& p) { return static_cast<std::size_t>(p.count("n")) + 1; },
       300},
      {"heavy_on_light",
       "stacking",
       "a size-m box, ratio times heavier, dropped on two 1 m boxes",
       {{"ratio", 400, 1, 1e6, false, "heavy mass / light mass"},
        {"size", 20, 1, 1000, false, "heavy box edge, m"},
        {"drop", 0.5, 0, 100, false, "gap it falls through, m"}},
       heavy_on_light,
       [](const SceneParams&) { return std::size_t{4}; },
       300},
      {"overlap_recovery",
       "stacking",
       "a pyramid created with each box overlapping its neighbours",
       {{"base", 4, 1, 200, true, "boxes in the bottom row"},
        {"overlap", 0.25, 0, 0.95, false, "fraction of a box"}},
       overlap_recovery,
       [](const SceneParams& p) { return triangle(p.count("base")) + 1; },
       300},
      {"random_pile",
       "stacking",
       "n boxes of mixed sizes dropped one by one into a container: a pile at rest",
       {{"n", 1000, 1, 2000000, true, "boxes"},
        {"seed", 1, 0, 2147483647, true, "layout seed"},
        {"layers", 0, 0, 1e6, false,
         "about how many boxes deep; 0: 2 sqrt(n) m wide, a deep pile"}},
       random_pile,
       [](const SceneParams& p) { return static_cast<std::size_t>(p.count("n")) + 3; },
       300},
  };
}

}  // namespace chainbench
