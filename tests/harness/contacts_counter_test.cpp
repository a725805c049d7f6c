// SPDX-License-Identifier: MIT
// The reference engines' contacts counter counts touching pairs, each once, awake or asleep: the
// benchmark reports it as the work each engine does per step.
#include "engines/registry.h"
#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <string>

namespace chainbench {
namespace {

double contacts(const Engine& engine) {
  const auto defs = engine.counter_defs();
  const auto values = engine.counters();
  for (std::size_t c = 0; c < defs.size() && c < values.size(); ++c) {
    if (defs[c].name == "contacts") return values[c];
  }
  ADD_FAILURE() << "no contacts counter";
  return -1.0;
}

// Steps `scene` in `spec` and returns the contacts counted after each of the given steps.
std::vector<double> contacts_at(const std::string& spec, const Scene& scene,
                                const std::vector<int>& steps) {
  const auto engine = make_engine(parse_engine_spec(spec), scene);
  std::vector<double> out;
  for (int step = 0; step <= steps.back(); ++step) {
    engine->step(step);
    for (const int k : steps) {
      if (k == step) out.push_back(contacts(*engine));
    }
  }
  return out;
}

// Three boxes stacked on the ground touch three times: box on ground, box on box, box on box.
// With sleeping on, the stack is asleep after half a second of rest (step 30), and its contacts
// are still there to count at step 120.
TEST(ContactsCounter, ThreeBoxStackOnTheGroundIsThreeContacts) {
  const Scene stack = make_scene("stack", {"n=3"});
  for (const char* spec : {"box2d", "box2d:sleep=1", "chipmunk", "chipmunk:sleep=1"}) {
    SCOPED_TRACE(spec);
    for (const double n : contacts_at(spec, stack, {0, 10, 120}))
      EXPECT_EQ(n, 3.0);
  }
}

// Top-down, no ground: a pusher and a row of three boxes, each touching the next, are three
// contacts; a stack of one box is one, with the ground.
TEST(ContactsCounter, CountsEachTouchingPairOnce) {
  for (const char* spec : {"box2d", "chipmunk"}) {
    SCOPED_TRACE(spec);
    EXPECT_EQ(contacts_at(spec, make_scene("push_row", {"n=3"}), {0})[0], 3.0);
    EXPECT_EQ(contacts_at(spec, make_scene("stack", {"n=1"}), {0})[0], 1.0);
  }
}

// Boxes a metre apart touch nothing: a falling box above an empty floor counts no contact until
// it lands.
TEST(ContactsCounter, BodiesApartAreNoContacts) {
  Scene s;
  s.name = "apart";
  build::ground(s, 10.0);
  build::box(s, "falling", BodyKind::kDynamic, {0.0, 3.0}, {0.5, 0.5});
  for (const char* spec : {"box2d", "chipmunk"}) {
    SCOPED_TRACE(spec);
    const std::vector<double> n = contacts_at(spec, s, {1, 120});
    EXPECT_EQ(n[0], 0.0);
    EXPECT_EQ(n[1], 1.0);  // fallen 2.5 m in 0.71 s, resting by 2 s
  }
}

}  // namespace
}  // namespace chainbench
