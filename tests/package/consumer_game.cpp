// What a C++17 game does with the solver: both public headers, a driven player pushing a box, and
// the C++17 views. Exits 0 when all went as expected.
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
  const chain::BodyId b = world.create_body(box);
  world.set_drive(p, {2.0, 0.0});
  for (int i = 0; i < 60; ++i)
    world.step(1.0 / 60.0);
  const std::vector<chain::BodyId> ids = {p, b};
  std::vector<chain::Vec2> positions(ids.size());
  world.read_state(ids, positions, {});
  chain::Span<const chain::CrushEvent> crushes = world.crush_events();

  std::printf("player %.3f box %.3f\n", positions[0].x, positions[1].x);
  const bool ok = positions[1].x > 1.5 && crushes.empty() && ids[0] != ids[1];
  return ok ? 0 : 1;
}
