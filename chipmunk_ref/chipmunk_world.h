// SPDX-License-Identifier: MIT
// The second reference: a Chipmunk2D 7 space built from a Scene and stepped the way the scene
// says.
//
// Boxes are box shapes without rounding; rotation is fixed by an infinite moment unless the scene
// rotates. Chipmunk lets contacts sink up to its collision slop before it pushes them apart (0.1,
// meant for pixels), so at rest its shapes overlap by the slop: with compensation (the default)
// each shape is built slop / 2 larger per side than its box, so that boxes rest at their declared
// faces, as Box2dWorld's skin compensation does. Friction and restitution of a contact combine as
// the scene format says (the square root of the product, and the larger of the two), not
// Chipmunk's product.
#pragma once

#include "model/drive_schedule.h"
#include "model/scene.h"

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

struct cpSpace;
struct cpBody;
struct cpShape;

namespace chainbench {

struct ChipmunkSettings {
  int iterations = 10;
  int substeps = 1;     // space steps per scene step
  double slop = 0.005;  // overlap contacts may keep, m (Chipmunk's own default: 0.1)
  // Share of an overlap left after one second of correction: Chipmunk's own, (1 - 0.1)^60.
  double bias = 0.001797010299914434;
  bool compensate_skin = true;
  bool sleep = false;  // bodies at rest fall asleep after 0.5 s, as games ship Chipmunk
};

class ChipmunkWorld {
 public:
  ChipmunkWorld(const Scene& scene, const ChipmunkSettings& settings);
  ~ChipmunkWorld();
  ChipmunkWorld(const ChipmunkWorld&) = delete;
  ChipmunkWorld& operator=(const ChipmunkWorld&) = delete;

  // Applies the drives the scene holds at step `step_index` (DriveSchedule), waking what they
  // move, then advances by the scene's dt in `substeps` space steps.
  void step(int step_index);
  // Centres, velocities and angles in scene order; a body not in the space is skipped.
  void read_state(std::span<Vec2d> positions, std::span<Vec2d> velocities,
                  std::span<double> angles) const;
  // Pairs whose shapes touch after the last step, sleeping ones included, each counted once.
  std::size_t touching_pairs() const;
  // Scene body i enters the space as the scene describes it, or leaves it (SceneBody::from_step);
  // the constructor adds the bodies of state 0.
  void add_body(std::size_t i);
  void remove_body(std::size_t i);

 private:
  struct SpaceDeleter {
    void operator()(cpSpace* space) const;
  };
  std::unique_ptr<cpSpace, SpaceDeleter> space_;
  const Scene& scene_;                 // outlives the space
  std::vector<cpBody*> bodies_;        // per scene body, null while it is not in the space
  std::vector<cpShape*> shapes_;       // per scene body, null while it is not in the space
  std::vector<double> gravity_scale_;  // per body; dynamic bodies point their user data here
  DriveSchedule drives_;
  double dt_;  // of one space step
  int substeps_;
  double grow_ = 0.0;  // what skin compensation adds to each half extent
};

}  // namespace chainbench
