// SPDX-License-Identifier: MIT
#include "box2d3/plain_pyramid.h"

#include <box2d/box2d.h>

namespace chainbench {

struct PlainBox2d3Pyramid::World {
  b2WorldId id;
};

// The pyramid scene's layout (bench/scenes/stacking.cpp), written out in v3 calls.
PlainBox2d3Pyramid::PlainBox2d3Pyramid(int base, int substeps)
    : world_(std::make_unique<World>()), substeps_(substeps) {
  b2WorldDef def = b2DefaultWorldDef();
  def.enableSleep = false;
  world_->id = b2CreateWorld(&def);

  b2BodyDef ground_def = b2DefaultBodyDef();
  ground_def.position = {0.0f, -1.0f};
  const b2BodyId ground = b2CreateBody(world_->id, &ground_def);
  b2ShapeDef shape = b2DefaultShapeDef();
  shape.material.friction = 0.0f;
  const b2Polygon floor = b2MakeBox(static_cast<float>(base) + 2.0f, 1.0f);
  b2CreatePolygonShape(ground, &shape, &floor);
  bodies_ = 1;

  const b2Polygon box = b2MakeBox(0.5f, 0.5f);  // density 1: 1 kg
  b2BodyDef body = b2DefaultBodyDef();
  body.type = b2_dynamicBody;
  body.fixedRotation = true;
  body.enableSleep = false;
  for (int row = 0; row < base; ++row) {
    for (int k = 0; k < base - row; ++k) {
      body.position = {static_cast<float>(k - 0.5 * (base - row - 1)), 0.5f + row};
      b2CreatePolygonShape(b2CreateBody(world_->id, &body), &shape, &box);
      ++bodies_;
    }
  }
}

PlainBox2d3Pyramid::~PlainBox2d3Pyramid() {
  b2DestroyWorld(world_->id);
}

void PlainBox2d3Pyramid::step() {
  b2World_Step(world_->id, 1.0f / 60.0f, substeps_);
}

}  // namespace chainbench
