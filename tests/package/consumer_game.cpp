// SPDX-License-Identifier: MIT
// What a C++17 game does with the solver: both public headers, a driven player pushing a box, a
// character walking with x held, friction, and the C++17 views. Exits 0 when all went as expected.
#include <chain/types.h>
#include <chain/world.h>

#include <cstdio>
#include <vector>

static_assert(__cplusplus == 201703L, "the consumer must be compiled as C++17");

int play() {
  chain::WorldDef def;
  def.gravity = {0.0, 0.0};
  chain::World world(def);
  chain::BodyDef player;
  const chain::BodyId p = world.create_body(player);
  chain::BodyDef box;
  box.center = {1.0, 0.0};
  box.friction = 0.5;
  const chain::BodyId b = world.create_body(box);
  world.set_drive(p, {2.0, 0.0});
  for (int i = 0; i < 60; ++i)
    world.step(1.0 / 60.0);
  const std::vector<chain::BodyId> ids = {p, b};
  std::vector<chain::Vec2> positions(ids.size());
  world.read_state(ids, positions, {});
  chain::Span<const chain::CrushEvent> crushes = world.crush_events();

  chain::World level;  // gravity on: a character walks off a ledge with only x held
  chain::BodyDef ledge;
  ledge.type = chain::BodyType::kStatic;
  ledge.center = {-5.0, -0.5};
  ledge.half_extents = {5.0, 0.5};
  level.create_body(ledge);
  chain::BodyDef hero;
  hero.center = {-0.5, 0.5};
  const chain::BodyId h = level.create_body(hero);
  level.set_drive(h, {4.0, 0.0}, chain::DriveAxes::kX);
  for (int i = 0; i < 60; ++i)
    level.step(1.0 / 60.0);

  std::printf("player %.3f box %.3f hero (%.3f, %.3f)\n", positions[0].x, positions[1].x,
              level.position(h).x, level.position(h).y);
  const bool ok =
      positions[1].x > 1.5 && crushes.empty() && ids[0] != ids[1] && level.position(h).y < -1.0;
  return ok ? 0 : 1;
}
