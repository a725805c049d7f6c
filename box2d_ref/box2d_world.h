// SPDX-License-Identifier: MIT
// The reference: a Box2D 2.4 world built from a Scene and stepped the way the scene says.
//
// Fixed rotation unless the scene asks for rotation; continuous collision against static and
// kinematic bodies on, as Box2D ships it; sleeping off unless asked for; each body's mass set
// exactly from the scene. Box2D pads every polygon with a skin of b2_polygonRadius (1 cm) and lets
// contacts rest about b2_linearSlop (5 mm) deep into it, so boxes built at their declared size rest
// about 1.5 cm apart. With compensation (the default) each polygon is built kSkinShrink smaller per
// side and boxes rest where their declared faces meet.
#pragma once

#include "model/drive_schedule.h"
#include "model/scene.h"

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

class b2World;
class b2ContactListener;
class b2Body;

namespace chainbench {

struct Box2dSettings {
  int velocity_iterations = 8;
  int position_iterations = 3;
  int substeps = 1;  // Box2D 2.4 has none of its own: each scene step is this many world steps
  bool compensate_skin = true;
  bool warm_starting = true;
  // Continuous collision: 0 off; 1 dynamic bodies against static and kinematic ones (Box2D's
  // own default); 2 every dynamic body a bullet, so also against other dynamic bodies.
  int continuous = 1;
  bool sleep = false;  // bodies at rest fall asleep, as games ship Box2D
};

class Box2dWorld {
 public:
  // b2_polygonRadius - b2_linearSlop / 2: what compensation takes off each side (7.5 mm).
  static double skin_shrink();
  // b2_maxTranslation: the farthest Box2D moves a body in one world step, m (2 in 2.4).
  static double max_translation();

  Box2dWorld(const Scene& scene, const Box2dSettings& settings);
  ~Box2dWorld();
  Box2dWorld(const Box2dWorld&) = delete;
  Box2dWorld& operator=(const Box2dWorld&) = delete;

  // Applies the drives the scene holds at step `step_index` (DriveSchedule), then advances by the
  // scene's dt.
  void step(int step_index);
  // Box2D's own timing of the last scene step (b2Profile), its world steps summed: its top-level
  // stages, milliseconds.
  struct Profile {
    double collide = 0.0;    // contacts updated (narrow phase)
    double solve = 0.0;      // islands solved, new pairs found (broad phase)
    double solve_toi = 0.0;  // continuous collision
  };
  const Profile& last_profile() const { return profile_; }
  // Contacts whose shapes touch after the last step.
  std::size_t touching_contacts() const;
  // Centres, velocities and angles in scene order; an empty span is skipped.
  void read_state(std::span<Vec2d> positions, std::span<Vec2d> velocities,
                  std::span<double> angles) const;
  std::size_t body_count() const { return bodies_.size(); }
  // Scene body i enters the world as the scene describes it, or leaves it (SceneBody::from_step);
  // the constructor adds the bodies of state 0. read_state skips a body not in the world.
  void add_body(std::size_t i);
  void remove_body(std::size_t i);

 private:
  // Conveyors (SceneBody::surface_velocity): sets each touching contact's tangent speed before
  // it is solved; null when the scene has none. Declared before world_, so it outlives it.
  std::unique_ptr<b2ContactListener> belts_;
  std::unique_ptr<b2World> world_;
  const Scene& scene_;           // outlives the world
  std::vector<b2Body*> bodies_;  // per scene body, null while it is not in the world
  DriveSchedule drives_;
  double dt_;
  Box2dSettings settings_;
  Profile profile_;
};

}  // namespace chainbench
