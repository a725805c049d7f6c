// SPDX-License-Identifier: MIT
// Fuzzes the chaining solver with small random worlds of boxes, stepped a few times (now and
// then a few dozen).
// For every valid world: each step returns, positions stay finite, static bodies never move, and
// (modern variant) the same bodies created in the opposite order end with the same bits, as do
// the same bodies solved every step (WorldDef::skip_rest off).
// Both variants and both velocity rules are fuzzed; modern three times as often.
#include "byte_reader.h"

#include <chain/world.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

// A failed check must stop the fuzzer with a reproducer; abort() is what libFuzzer catches.
void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "world_fuzz: %s\n", what);
  std::abort();
}

struct FuzzCase {
  chain::WorldDef world;
  std::vector<chain::BodyDef> bodies;
  std::vector<bool> driven;
  std::vector<chain::Vec2> drive;
  double dt = 1.0 / 60.0;
  int steps = 1;
  int destroy_at = -1;  // step before which body `destroy_index` is destroyed
  int destroy_index = 0;
};

FuzzCase read_case(fuzz::ByteReader& in) {
  FuzzCase c;
  // Mostly short cases (at most 8 steps and 12 bodies), for throughput; one in 16 is long (up to
  // 60 steps, 24 bodies). A leading 0 byte makes any input long, as every input was before.
  const bool long_case = in.pick(16) == 0;
  c.world.variant = in.pick(4) == 0 ? chain::Variant::kSeed2014 : chain::Variant::kModern;
  c.world.velocity_rule = in.flag() ? chain::VelocityRule::kInelastic : chain::VelocityRule::kZero;
  c.world.gravity = {in.grid(-20.0, 0.15625), in.grid(-20.0, 0.15625)};
  c.world.max_passes = 1 + in.pick(8);
  c.world.budget_per_body = 1 + in.pick(128);
  constexpr double kSteps[] = {1.0 / 1000.0, 1.0 / 240.0, 1.0 / 60.0, 1.0 / 30.0, 1.0 / 10.0};
  c.dt = kSteps[in.pick(5)];
  c.steps = 1 + in.pick(long_case ? 60 : 8);
  const int n = 1 + in.pick(long_case ? 24 : 12);
  for (int i = 0; i < n; ++i) {
    chain::BodyDef b;
    const int type = in.pick(4);
    b.type = type == 0 ? chain::BodyType::kStatic
                       : (type == 1 ? chain::BodyType::kKinematic : chain::BodyType::kDynamic);
    // Centres on a 1/16 m grid and sizes on a 1/16 m grid: touching and stacking are common.
    b.center = {in.grid(-8.0, 0.0625), in.grid(-8.0, 0.0625)};
    b.half_extents = {0.0625 * (1 + in.pick(32)), 0.0625 * (1 + in.pick(32))};
    if (b.type != chain::BodyType::kStatic)
      b.velocity = {in.grid(-16.0, 0.125), in.grid(-16.0, 0.125)};
    if (b.type == chain::BodyType::kDynamic) {
      b.mass = in.decades(-3, 6);
      b.gravity_scale = in.flag() ? 1.0 : 0.0;
      b.restitution = 0.5 * in.pick(3);
    }
    c.bodies.push_back(b);
    const bool driven = b.type != chain::BodyType::kStatic && in.pick(4) == 0;
    c.driven.push_back(driven);
    c.drive.push_back(driven ? chain::Vec2{in.grid(-8.0, 0.0625), in.grid(-8.0, 0.0625)}
                             : chain::Vec2{});
  }
  if (in.flag()) {
    c.destroy_at = in.pick(c.steps);
    c.destroy_index = in.pick(n);
  }
  return c;
}

// Builds the world with bodies created in `order`; ids[i] is body i's id.
chain::World build(const FuzzCase& c, const std::vector<int>& order,
                   std::vector<chain::BodyId>& ids) {
  chain::World world(c.world);
  ids.assign(c.bodies.size(), chain::BodyId{});
  for (int i : order) {
    const auto k = static_cast<std::size_t>(i);
    ids[k] = world.create_body(c.bodies[k]);
    if (c.driven[k]) world.set_drive(ids[k], c.drive[k]);
  }
  return world;
}

// One surviving body: what defines it, then where it ended.
using Row = std::array<double, 15>;

// Steps the world through the case; returns a row per surviving body, sorted. Sorted, because
// identical bodies (same definition, same place) may trade places with the creation order and
// nothing can tell them apart: the promise is the same bits for the same set of bodies.
std::vector<Row> run(const FuzzCase& c, chain::World& world,
                     const std::vector<chain::BodyId>& ids) {
  std::vector<bool> alive(c.bodies.size(), true);
  for (int step = 0; step < c.steps; ++step) {
    if (step == c.destroy_at) {
      world.destroy_body(ids[static_cast<std::size_t>(c.destroy_index)]);
      alive[static_cast<std::size_t>(c.destroy_index)] = false;
    }
    world.step(c.dt);
    for (std::size_t i = 0; i < c.bodies.size(); ++i) {
      if (!alive[i]) continue;
      const chain::Vec2 p = world.position(ids[i]);
      require(std::isfinite(p.x) && std::isfinite(p.y), "a position is not finite");
      if (c.bodies[i].type == chain::BodyType::kStatic) {
        require(p.x == c.bodies[i].center.x && p.y == c.bodies[i].center.y, "a static body moved");
      }
    }
  }
  std::vector<Row> rows;
  for (std::size_t i = 0; i < c.bodies.size(); ++i) {
    if (!alive[i]) continue;
    const chain::BodyDef& b = c.bodies[i];
    const chain::Vec2 p = world.position(ids[i]);
    rows.push_back({static_cast<double>(b.type), b.center.x, b.center.y, b.half_extents.x,
                    b.half_extents.y, b.velocity.x, b.velocity.y, b.mass, b.gravity_scale,
                    b.restitution, c.driven[i] ? 1.0 : 0.0, c.drive[i].x, c.drive[i].y, p.x, p.y});
  }
  std::sort(rows.begin(), rows.end());
  return rows;
}

// Whether another body was created identical to body k (every field of its definition, and its
// drive): only such bodies may trade places (world.h), so destroying one of them by index may
// remove different bodies in two worlds. Bodies created apart are told apart by the solver even
// where they reach one state.
bool has_twin(const FuzzCase& c, std::size_t k) {
  const chain::BodyDef& a = c.bodies[k];
  for (std::size_t i = 0; i < c.bodies.size(); ++i) {
    const chain::BodyDef& b = c.bodies[i];
    if (i != k && a.type == b.type && a.center.x == b.center.x && a.center.y == b.center.y &&
        a.half_extents.x == b.half_extents.x && a.half_extents.y == b.half_extents.y &&
        a.velocity.x == b.velocity.x && a.velocity.y == b.velocity.y && a.mass == b.mass &&
        a.gravity_scale == b.gravity_scale && a.restitution == b.restitution &&
        a.friction == b.friction && c.driven[i] == c.driven[k] && c.drive[i].x == c.drive[k].x &&
        c.drive[i].y == c.drive[k].y) {
      return true;
    }
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader in(data, size);
  const FuzzCase c = read_case(in);
  std::vector<int> order(c.bodies.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = static_cast<int>(i);
  std::vector<chain::BodyId> ids;
  chain::World forward = build(c, order, ids);
  const std::vector<Row> a = run(c, forward, ids);
  // seed2014 resolves in creation order, as the 2014 engine did: only modern promises this.
  if (c.world.variant != chain::Variant::kModern) return 0;
  // Bodies created identical may trade places, so destroying one of them by index removes
  // different bodies in the two worlds.
  if (c.destroy_at >= 0 && has_twin(c, static_cast<std::size_t>(c.destroy_index))) return 0;
  std::vector<int> reversed(order.rbegin(), order.rend());
  chain::World backward = build(c, reversed, ids);
  require(run(c, backward, ids) == a, "creation order changed a final position");
  // Skipping the steps of a world at rest changes nothing (WorldDef::skip_rest).
  FuzzCase solved = c;
  solved.world.skip_rest = false;
  chain::World every_step = build(solved, order, ids);
  require(run(solved, every_step, ids) == a, "skip_rest changed a final position");
  return 0;
}
