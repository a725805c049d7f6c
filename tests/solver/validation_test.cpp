// SPDX-License-Identifier: MIT
// Bad input is refused when it is added, with a reason that names the field; the world is left
// as it was.
#include "world_helpers.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace chain::testing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct BadBody {
  const char* name;
  BodyDef def;
  const char* field;  // the reason must name it
};
void PrintTo(const BadBody& c, std::ostream* os) {
  *os << c.name;
}

BodyDef with(BodyDef d, void (*edit)(BodyDef&)) {
  edit(d);
  return d;
}

class RejectedBody : public ::testing::TestWithParam<BadBody> {};

INSTANTIATE_TEST_SUITE_P(
    Validation, RejectedBody,
    ::testing::Values(
        BadBody{"NaNCenter", with(dynamic_box(0, 0), [](BodyDef& d) { d.center.x = kNaN; }),
                "center.x"},
        BadBody{"InfiniteCenter", with(dynamic_box(0, 0), [](BodyDef& d) { d.center.y = -kInf; }),
                "center.y"},
        BadBody{"FarCenter", with(dynamic_box(0, 0), [](BodyDef& d) { d.center.x = 3e9; }),
                "center.x"},
        BadBody{"ZeroHalfExtent", with(dynamic_box(0, 0), [](BodyDef& d) { d.half_extents.x = 0; }),
                "half_extents.x"},
        BadBody{"NegativeHalfExtent",
                with(dynamic_box(0, 0), [](BodyDef& d) { d.half_extents.y = -1; }),
                "half_extents.y"},
        BadBody{"NaNHalfExtent",
                with(dynamic_box(0, 0), [](BodyDef& d) { d.half_extents.y = kNaN; }),
                "half_extents.y"},
        BadBody{"InfiniteHalfExtent",
                with(dynamic_box(0, 0), [](BodyDef& d) { d.half_extents.x = kInf; }),
                "half_extents.x"},
        BadBody{"ZeroMass", with(dynamic_box(0, 0), [](BodyDef& d) { d.mass = 0; }), "mass"},
        BadBody{"NegativeMass", with(dynamic_box(0, 0), [](BodyDef& d) { d.mass = -2; }), "mass"},
        BadBody{"NaNMass", with(dynamic_box(0, 0), [](BodyDef& d) { d.mass = kNaN; }), "mass"},
        BadBody{"InfiniteMass", with(dynamic_box(0, 0), [](BodyDef& d) { d.mass = kInf; }), "mass"},
        BadBody{"NaNVelocity", with(dynamic_box(0, 0), [](BodyDef& d) { d.velocity.y = kNaN; }),
                "velocity.y"},
        BadBody{"MovingStatic", with(static_box(0, 0, 1, 1), [](BodyDef& d) { d.velocity.x = 1; }),
                "velocity"},
        BadBody{"RestitutionAboveOne",
                with(dynamic_box(0, 0), [](BodyDef& d) { d.restitution = 1.5; }), "restitution"},
        BadBody{"NaNGravityScale",
                with(dynamic_box(0, 0), [](BodyDef& d) { d.gravity_scale = kNaN; }),
                "gravity_scale"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_P(RejectedBody, IsRefusedWithItsFieldNamed) {
  const BadBody& bad = GetParam();
  EXPECT_NE(validate(bad.def).find(bad.field), std::string::npos) << validate(bad.def);
  World w;
  try {
    w.create_body(bad.def);
    FAIL() << "accepted " << bad.name;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(bad.field), std::string::npos) << e.what();
  }
  EXPECT_EQ(w.body_count(), 0u);
}

TEST(Validation, MassOfStaticAndKinematicBodiesIsIgnored) {
  BodyDef lift = kinematic_box(0, 0, 1, 1, {0, 1});
  lift.mass = -1.0;
  EXPECT_EQ(validate(lift), "");
  BodyDef ground = static_box(0, 0, 1, 1);
  ground.mass = 0.0;
  EXPECT_EQ(validate(ground), "");
}

TEST(Validation, StepRejectsNonPositiveOrNonFiniteDt) {
  World w;
  w.create_body(dynamic_box(0, 0));
  for (const double dt : {0.0, -0.01, kNaN, kInf}) {
    EXPECT_THROW(w.step(dt), std::invalid_argument) << dt;
  }
  EXPECT_NO_THROW(w.step(1.0 / 60.0));
}

TEST(Validation, WorldDefOutOfRangeIsRefused) {
  WorldDef d;
  d.max_passes = 0;
  EXPECT_THROW(World{d}, std::invalid_argument);
  d = WorldDef{};
  d.gravity.y = kNaN;
  EXPECT_NE(validate(d).find("gravity.y"), std::string::npos);
  d = WorldDef{};
  d.seed_max_depth = 1 << 20;
  EXPECT_NE(validate(d).find("seed_max_depth"), std::string::npos);
  EXPECT_EQ(validate(WorldDef{}), "");
}

TEST(Validation, UnknownOrDestroyedIdsAreRefused) {
  World w;
  const BodyId a = w.create_body(dynamic_box(0, 0));
  const BodyId b = w.create_body(dynamic_box(3, 0));
  w.destroy_body(a);
  EXPECT_FALSE(w.contains(a));
  EXPECT_THROW(w.position(a), std::invalid_argument);
  EXPECT_THROW(w.destroy_body(a), std::invalid_argument);
  EXPECT_THROW(w.position(BodyId{99}), std::invalid_argument);
  EXPECT_TRUE(w.contains(b));
  EXPECT_FLOAT_EQ(w.position(b).x, 3.0);
  // Ids are never reused.
  EXPECT_NE(w.create_body(dynamic_box(0, 0)), a);
}

TEST(Validation, StaticBodiesCannotBeDriven) {
  World w;
  const BodyId ground = w.create_body(static_box(0, 0, 1, 1));
  EXPECT_THROW(w.set_drive(ground, {1, 0}), std::invalid_argument);
  const BodyId box = w.create_body(dynamic_box(5, 5));
  EXPECT_THROW(w.set_drive(box, {kNaN, 0}), std::invalid_argument);
}

// Valid but extreme: the solver must neither produce NaN nor stall.
TEST(Validation, ExtremeValidInputStaysFinite) {
  for (const Variant v : {Variant::kModern, Variant::kSeed2014}) {
    World w(world_def(v, VelocityRule::kInelastic));
    std::vector<BodyId> ids = {add_floor(w, 1e6)};
    ids.push_back(w.create_body(dynamic_box(0.0, 0.5, 0.5, 1e-6)));
    ids.push_back(w.create_body(dynamic_box(0.2, 1.4, 0.5, 1e12)));     // 1e18:1 on top
    ids.push_back(w.create_body(dynamic_box(3.0, 0.0, 1e-4, 1.0)));     // tiny, inside the floor
    ids.push_back(w.create_body(dynamic_box(8.0, 500.0, 200.0, 1e3)));  // huge, falling
    BodyDef fast = dynamic_box(-20.0, 3.0);
    fast.velocity = {9e5, -9e5};
    ids.push_back(w.create_body(fast));
    for (int s = 0; s < 120; ++s) {
      w.step(1.0 / 60.0);
      for (const BodyId id : ids) {
        const Vec2 p = w.position(id), vel = w.velocity(id);
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(vel.x) &&
                    std::isfinite(vel.y))
            << variant_name(v) << " step " << s;
      }
    }
  }
}

}  // namespace
}  // namespace chain::testing
