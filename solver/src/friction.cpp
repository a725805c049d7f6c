// SPDX-License-Identifier: MIT
#include "friction.h"

#include "buffer.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {
namespace {

constexpr std::uint32_t kUnreached = 0xffffffffu;
constexpr std::uint32_t kUnnumbered = 0xffffffffu;  // local_ of a slot no link touches

// The velocity along axis t friction sees at body i's surface: its own, and a conveyor's belt on
// top of it (BodyDef::surface_velocity).
double surface_speed(const Bodies& bodies, std::uint32_t i, int t) {
  const double v = t == 0 ? bodies.vx[i] : bodies.vy[i];
  if (bodies.surface.empty()) return v;
  return v + (t == 0 ? bodies.surface[i].x : bodies.surface[i].y);
}

}  // namespace

bool Friction::slides(const Bodies& bodies, const Link& l) {
  const int t = 1 - l.axis;
  const double* v = t == 0 ? bodies.vx.data() : bodies.vy.data();
  const std::uint8_t held = t == 0 ? kDriveX : kDriveY;
  const bool free_a = !bodies.immovable(l.a) && !(bodies.driven[l.a] & held);
  const bool free_b = !bodies.immovable(l.b) && !(bodies.driven[l.b] & held);
  if (!free_a && !free_b) return false;  // nothing friction may change
  if (!bodies.surface.empty() && surface_speed(bodies, l.a, t) != surface_speed(bodies, l.b, t))
    return true;
  // Equal velocities give a zero impulse, which still turns a's -0 into +0.
  return v[l.a] != v[l.b] || (v[l.a] == 0.0 && std::signbit(v[l.a]));
}

void Friction::number_bodies(const Bodies& bodies, const std::vector<Link>& links) {
  if (local_.size() != bodies.size()) assign_buffer(local_, bodies.size(), kUnnumbered);
  bodies_.clear();
  auto number = [&](std::uint32_t slot) {
    if (bodies.immovable(slot) || local_[slot] != kUnnumbered) return;
    local_[slot] = static_cast<std::uint32_t>(bodies_.size());
    bodies_.push_back(slot);
  };
  for (const Link& l : links) {
    number(l.a);
    number(l.b);
  }
}

void Friction::normal_impulses(const Bodies& bodies, const std::vector<Link>& links,
                               const std::vector<Point>& pre_velocity, int axis) {
  const auto m = static_cast<std::uint32_t>(bodies_.size());
  const auto n_links = static_cast<std::uint32_t>(links.size());
  // Adjacency: per local body, the links along axis it takes part in.
  adj_start_.assign(m + 2, 0);
  for (const Link& l : links) {
    if (l.axis != axis) continue;
    ++adj_start_[local(l.a) + 2];
    if (!bodies.immovable(l.b)) ++adj_start_[local(l.b) + 2];
  }
  for (std::uint32_t i = 2; i < m + 2; ++i)
    adj_start_[i] += adj_start_[i - 1];
  resize_buffer(adj_, adj_start_[m + 1]);
  for (std::uint32_t k = 0; k < n_links; ++k) {  // adj_start_[i + 1] is the fill cursor of i
    const Link& l = links[k];
    if (l.axis != axis) continue;
    adj_[adj_start_[local(l.a) + 1]++] = k;
    if (!bodies.immovable(l.b)) adj_[adj_start_[local(l.b) + 1]++] = k;
  }
  // Levels by contact-graph distance from the immovable bodies (level 0); a group that touches
  // none grows from its first body in step order.
  level_.assign(m, kUnreached);
  queue_.clear();
  auto other = [&](const Link& l, std::uint32_t u) { return bodies_[u] == l.a ? l.b : l.a; };
  auto grow = [&](std::size_t from) {
    for (std::size_t q = from; q < queue_.size(); ++q) {
      const std::uint32_t u = queue_[q];
      for (std::uint32_t e = adj_start_[u]; e < adj_start_[u + 1]; ++e) {
        const std::uint32_t o = other(links[adj_[e]], u);
        if (bodies.immovable(o) || level_[local(o)] != kUnreached) continue;
        level_[local(o)] = level_[u] + 1;
        queue_.push_back(local(o));
      }
    }
  };
  for (const Link& l : links) {
    if (l.axis != axis || !bodies.immovable(l.b) || level_[local(l.a)] != kUnreached) continue;
    level_[local(l.a)] = 1;
    queue_.push_back(local(l.a));
  }
  grow(0);
  for (const Link& l : links) {
    if (l.axis != axis) continue;
    for (const std::uint32_t slot : {l.a, l.b}) {
      if (bodies.immovable(slot) || level_[local(slot)] != kUnreached) continue;
      const std::size_t from = queue_.size();
      level_[local(slot)] = 1;
      queue_.push_back(local(slot));
      grow(from);
    }
  }
  // Each body's momentum change, plus what it passed on to the bodies it holds up, goes down to
  // its supports (the neighbours of a lower level), farthest bodies first.
  resize_buffer(carried_, m);
  for (const std::uint32_t u : queue_) {
    const std::uint32_t slot = bodies_[u];
    const double v = axis == 0 ? bodies.vx[slot] : bodies.vy[slot];
    const double v0 = axis == 0 ? pre_velocity[slot].x : pre_velocity[slot].y;
    carried_[u] = bodies.mass[slot] * (v - v0);
  }
  auto supports = [&](const Link& l, std::uint32_t u) {
    const std::uint32_t o = other(l, u);
    return bodies.immovable(o) || level_[local(o)] < level_[u];
  };
  for (std::size_t q = queue_.size(); q-- > 0;) {
    const std::uint32_t u = queue_[q];
    std::uint32_t count = 0;
    for (std::uint32_t e = adj_start_[u]; e < adj_start_[u + 1]; ++e)
      count += supports(links[adj_[e]], u) ? 1u : 0u;
    if (count == 0) continue;
    const double share = carried_[u] / static_cast<double>(count);
    for (std::uint32_t e = adj_start_[u]; e < adj_start_[u + 1]; ++e) {
      const Link& l = links[adj_[e]];
      if (!supports(l, u)) continue;
      // The support pushes u along l.sign when u is the pushed body a, against it otherwise.
      normal_[adj_[e]] += (bodies_[u] == l.a ? 1.0 : -1.0) * l.sign * share;
      const std::uint32_t o = other(l, u);
      if (!bodies.immovable(o)) carried_[local(o)] += share;
    }
  }
}

void Friction::apply(Bodies& bodies, Broadphase& broadphase, const std::vector<Link>& links,
                     const std::vector<Point>& pre_velocity, double dt, double tolerance,
                     Reach* reach) {
  if (links.empty()) return;
  const std::size_t n_links = links.size();
  // Per body, as many as the world has; per link, as many as this step has, growing by a quarter
  // (buffer.h): sized for as many links as the link list could hold, they held 80 bytes a body
  // in a rough pile, most of them unused. A step busier than any before allocates once.
  for (auto* v : {&bodies_, &level_, &adj_start_, &queue_})
    reserve_buffer(*v, bodies.size() + 2);
  reserve_buffer(carried_, bodies.size());
  reserve_buffer(v_before_, bodies.size());
  assign_buffer(limit_, n_links, 0.0);
  active_.clear();
  reserve_buffer(active_, n_links);
  bool any = false;
  for (std::size_t k = 0; k < n_links; ++k) {
    limit_[k] = std::sqrt(bodies.friction[links[k].a] * bodies.friction[links[k].b]);
    any = any || (limit_[k] > 0.0 && slides(bodies, links[k]));
  }
  // No rough contact slides: every impulse of the solve would be zero and change no bit.
  if (!any) return;
  number_bodies(bodies, links);
  // local_ back to unnumbered for the next step, however this one ends: the work is the bodies
  // numbered, and no per-slot mark is kept beside it.
  struct Unnumber {
    std::vector<std::uint32_t>& local;
    const std::vector<std::uint32_t>& numbered;
    ~Unnumber() {
      for (const std::uint32_t slot : numbered)
        local[slot] = kUnnumbered;
    }
  } unnumber{local_, bodies_};
  // Both axes' normal impulses come from the velocities the velocity rule left, before any
  // friction changes them.
  assign_buffer(normal_, n_links, 0.0);
  normal_impulses(bodies, links, pre_velocity, 0);
  normal_impulses(bodies, links, pre_velocity, 1);
  for (std::size_t k = 0; k < n_links; ++k) {
    limit_[k] *= std::max(0.0, normal_[k]);
    if (limit_[k] > 0.0) active_.push_back(static_cast<std::uint32_t>(k));
  }
  if (active_.empty()) return;

  resize_buffer(v_before_, bodies_.size());
  for (std::size_t u = 0; u < bodies_.size(); ++u)
    v_before_[u] = {bodies.vx[bodies_[u]], bodies.vy[bodies_[u]]};
  assign_buffer(applied_, n_links, 0.0);
  auto inverse_mass = [&](std::uint32_t slot, int t) {
    if (bodies.immovable(slot) || (bodies.driven[slot] & (t == 0 ? kDriveX : kDriveY))) return 0.0;
    return 1.0 / bodies.mass[slot];
  };
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    // An iteration that applies no impulse leaves every velocity as the next one finds it (but
    // for -0 turned +0, which that iteration did already): the rest would apply none either.
    bool changed = false;
    for (const std::uint32_t k : active_) {
      const Link& l = links[k];
      const int t = 1 - l.axis;
      double* v = t == 0 ? bodies.vx.data() : bodies.vy.data();
      const double inv_a = inverse_mass(l.a, t), inv_b = inverse_mass(l.b, t);
      if (inv_a + inv_b == 0.0) continue;
      const double belt = bodies.surface.empty()
                              ? 0.0
                              : (t == 0 ? bodies.surface[l.b].x - bodies.surface[l.a].x
                                        : bodies.surface[l.b].y - bodies.surface[l.a].y);
      const double wanted = -(v[l.a] - v[l.b] - belt) / (inv_a + inv_b);
      const double total = std::clamp(applied_[k] + wanted, -limit_[k], limit_[k]);
      const double impulse = total - applied_[k];
      applied_[k] = total;
      v[l.a] += impulse * inv_a;
      v[l.b] -= impulse * inv_b;
      changed = changed || impulse != 0.0;
    }
    if (!changed) break;
  }
  place(bodies, broadphase, dt, tolerance, reach);
}

void Friction::place(Bodies& bodies, Broadphase& broadphase, double dt, double tolerance,
                     Reach* reach) {
  // Local body k's move along axis t: half the velocity friction took off, times dt.
  auto move_of = [&](std::uint32_t k, int t) {
    const std::uint32_t slot = bodies_[k];
    return 0.5 *
           ((t == 0 ? bodies.vx[slot] : bodies.vy[slot]) -
            (t == 0 ? v_before_[k].x : v_before_[k].y)) *
           dt;
  };
  // The movers of one axis, front first, in queue_ (the levels' queue, done with by now: it has
  // room for every body the links touch).
  std::vector<std::uint32_t>& order = queue_;
  for (int t = 0; t < 2; ++t) {
    const int u = 1 - t;
    order.clear();
    for (std::uint32_t k = 0; k < bodies_.size(); ++k)
      if (move_of(k, t) != 0.0) order.push_back(k);
    // Front first: a body moves before the ones behind it that follow it into the room it left.
    auto ahead = [&](std::uint32_t k) {
      return (move_of(k, t) > 0.0 ? 1.0 : -1.0) * bodies.pos(t, bodies_[k]);
    };
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const double pa = ahead(a), pb = ahead(b);
      return pa != pb ? pa > pb : bodies_[a] < bodies_[b];
    });
    for (const std::uint32_t k : order) {
      const std::uint32_t i = bodies_[k];
      const double d = move_of(k, t);
      const double sign = d > 0.0 ? 1.0 : -1.0;
      double move = std::abs(d);
      // The bodies across the path that overlap i along the other axis: the move stops where i
      // would touch the nearest one ahead (at once, against one it touches).
      double centre[2] = {bodies.x(i), bodies.y(i)}, half[2] = {bodies.hx(i), bodies.hy(i)};
      centre[t] += 0.5 * sign * move;
      half[t] += 0.5 * move;
      broadphase.for_each_in_box(
          bodies, centre[0], centre[1], half[0], half[1], tolerance, [&](std::uint32_t j) {
            if (j == i || !bodies.collides(i, j)) return;
            const double across = bodies.half(u, i) + bodies.half(u, j) -
                                  std::abs(bodies.pos(u, i) - bodies.pos(u, j));
            if (across <= tolerance) return;
            const double gap = sign * (bodies.pos(t, j) - bodies.pos(t, i));
            if (gap <= 0.0) return;  // behind i's centre: moving on takes i out of it
            move = std::min(move, std::max(0.0, gap - bodies.half(t, i) - bodies.half(t, j)));
          });
      if (move == 0.0) continue;
      bodies.pos(t, i) += sign * move;
      broadphase.note_move(i, bodies.x(i), bodies.y(i));
      if (reach != nullptr) reach->note(i, bodies.x(i), bodies.y(i));
    }
  }
}

}  // namespace chain::detail
