// SPDX-License-Identifier: MIT
// Coulomb friction for the modern variant, after the velocity rule.
//
// Every push of the step is a contact along its axis (the normal); friction acts along the other
// axis, with the coefficient sqrt(fa * fb) (the geometric mean rigid-body engines commonly use),
// bounded by mu times the contact's normal impulse.
//
// The normal impulse. Push-out leaves no forces behind, only velocity changes, so a contact's
// normal impulse is the momentum the step took out of the bodies it holds up: each dynamic body's
// m * dv along the normal (from its velocity after drives and gravity to its velocity after
// push-out and the velocity rule) is handed down its supports, from the bodies farthest from an
// immovable body (by contact-graph distance along that axis) to the nearest, and split evenly
// where a body rests on several. The bottom contact of a resting stack of total mass M thus
// carries M * g * dt each step, its whole weight, and a stack on a moving platform is carried as
// a whole. With the zero rule, dv is the velocity the push stopped; with the inelastic rule, what
// the shared group velocity (and any bounce) changed.
//
// The tangential impulses are solved by sequential impulses over the contacts, in the order the
// step made them (outward from immovable bodies), each clamped to [-mu jn, mu jn]. A drive's held
// velocity components are never changed: along them the body counts as immovable. Friction acts
// over the whole step, so a body also moves by half the velocity it took off times dt (the
// trapezoidal rule): a box sliding at v stops after v^2 / (2 mu g), not a step's travel beyond.
// That move never takes a body into another (a crate carried into a wall, or slowed back into
// the pusher behind it): it stops where the body would touch the first body across its path,
// axis by axis, the bodies in front moving first so that those behind may follow.
#pragma once

#include "bodies.h"
#include "broadphase.h"
#include "reach.h"
#include "velocity_response.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

class Friction {
 public:
  // `pre_velocity`: per dynamic slot, the velocity after drives and gravity, before push-out.
  // Each move is noted in `reach` (may be null) as well as in the broadphase.
  // `tolerance`: WorldDef::touch_tolerance, m.
  void apply(Bodies& bodies, Broadphase& broadphase,
             const std::vector<VelocityResponse::Link>& links,
             const std::vector<Point>& pre_velocity, double dt, double tolerance, Reach* reach);

 private:
  using Link = VelocityResponse::Link;
  // Sequential-impulse sweeps over the contacts: a stack of k boxes needs about k to share one
  // acceleration, and more change the result by less than a millimetre per second.
  static constexpr int kIterations = 8;

  // True unless the solve would leave the link's bodies as they are: no tangential relative
  // velocity, or no body it may change (immovable, or driven along the tangent).
  static bool slides(const Bodies& bodies, const Link& l);
  // Numbers the dynamic bodies the links touch (local_ of a slot, bodies_ of a number).
  void number_bodies(const Bodies& bodies, const std::vector<Link>& links);
  // Fills normal_ for the links along axis.
  void normal_impulses(const Bodies& bodies, const std::vector<Link>& links,
                       const std::vector<Point>& pre_velocity, int axis);
  std::uint32_t local(std::uint32_t slot) const { return local_[slot]; }
  // Moves each body by the trapezoidal rule's share (half what friction took off its velocity,
  // times dt), cut short where it would meet another body.
  void place(Bodies& bodies, Broadphase& broadphase, double dt, double tolerance, Reach* reach);

  std::vector<double> normal_, limit_, applied_;  // per link
  std::vector<std::uint32_t> active_;             // links that can rub, in step order
  std::vector<std::uint32_t> local_;   // per slot: its local number, unnumbered between steps
  std::vector<std::uint32_t> bodies_;  // per local body: its slot
  std::vector<std::uint32_t> level_, adj_start_, adj_, queue_;
  std::vector<double> carried_;
  std::vector<Point> v_before_;
};

}  // namespace chain::detail
