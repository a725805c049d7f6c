// Pushes a box with a driven player through the installed package; exits 0 when the box moved.
#include <chain/world.h>

#include <cstdio>

int main() {
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
  std::printf("player %.3f box %.3f\n", world.position(p).x, world.position(b).x);
  return world.position(b).x > 1.5 ? 0 : 1;
}
