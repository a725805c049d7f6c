// SPDX-License-Identifier: MIT
// Fuzzes the scene-file loader. Any text must either be refused with an InputError or load as
// a scene that every engine can build and step a few times with finite results.
#include "engines/registry.h"
#include "scenes/scene_file.h"
#include "support/input_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace {

void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "scene_file_fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace chainbench;
  Scene scene;
  try {
    scene = parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const InputError&) {
    return 0;  // refused, with a message: the right answer to bad input
  }
  // Stepping is to show a loaded scene is one the engines accept; a few small ones suffice.
  if (scene.bodies.size() > 64) return 0;
  for (const char* spec : {"chain", "chain:variant=seed2014,velocity=zero", "box2d"}) {
    std::unique_ptr<Engine> engine;
    try {
      engine = make_engine(parse_engine_spec(spec), scene);
    } catch (const InputError&) {
      continue;  // a scene the engine cannot run (rotation, friction...), refused by name
    }
    for (int step = 0; step < std::min(scene.steps, 10); ++step)
      engine->step(step);
    BodyState state(scene.bodies.size());
    engine->read_state(state);
    for (const Vec2d& p : state.position)
      require(std::isfinite(p.x) && std::isfinite(p.y), spec);
  }
  return 0;
}
