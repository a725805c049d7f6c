// SPDX-License-Identifier: MIT
// Reading a World: bodies one by one or all at once.
#include "world_impl.h"

#include <bit>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace chain {

Vec2 World::position(BodyId id) const {
  const std::uint32_t s = impl_->slot(id);
  return {impl_->bodies.x(s), impl_->bodies.y(s)};
}

Vec2 World::velocity(BodyId id) const {
  const std::uint32_t s = impl_->slot(id);
  return {impl_->bodies.vx[s], impl_->bodies.vy[s]};
}

std::uint8_t World::touching_flags(BodyId id) const {
  return static_cast<std::uint8_t>(impl_->bodies.touching[impl_->slot(id)]);
}

void World::read_state(Span<const BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities) const {
  const detail::Bodies& b = impl_->bodies;
  if ((!positions.empty() && positions.size() < ids.size()) ||
      (!velocities.empty() && velocities.size() < ids.size())) {
    throw std::invalid_argument("read_state: an output span is shorter than ids");
  }
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::uint32_t s = impl_->slot(ids[k]);
    if (!positions.empty()) positions[k] = {b.x(s), b.y(s)};
    if (!velocities.empty()) velocities[k] = {b.vx[s], b.vy[s]};
  }
}

// Entry k of read_all's outputs is the k-th slot that holds a body: dead slots (Bodies::kill)
// are passed over, so that a world with none costs one test a slot.
void World::read_all(Span<BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities) const {
  const detail::Bodies& b = impl_->bodies;
  const std::size_t n = impl_->live();
  if ((!ids.empty() && ids.size() < n) || (!positions.empty() && positions.size() < n) ||
      (!velocities.empty() && velocities.size() < n)) {
    throw std::invalid_argument("read_all: an output span is shorter than body_count()");
  }
  std::size_t k = 0;
  for (std::uint32_t s = 0; s < b.size(); ++s) {
    if (b.dead(s)) continue;
    if (!ids.empty()) ids[k] = BodyId{b.id[s]};
    if (!positions.empty()) positions[k] = {b.box[s].center[0], b.box[s].center[1]};
    if (!velocities.empty()) velocities[k] = {b.vx[s], b.vy[s]};
    ++k;
  }
}

void World::update_all(Span<BodyId> ids, Span<Vec2> positions, Span<Vec2> velocities,
                       std::vector<std::uint32_t>& changed) const {
  const detail::Bodies& b = impl_->bodies;
  const std::size_t n = impl_->live();
  if (ids.size() < n || positions.size() < n || velocities.size() < n) {
    throw std::invalid_argument("update_all: an output span is shorter than body_count()");
  }
  changed.clear();
  auto same = [](double a, double c) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(c) && a == a;
  };
  std::uint32_t k = 0;
  for (std::uint32_t s = 0; s < b.size(); ++s) {
    if (b.dead(s)) continue;
    const Vec2 p{b.box[s].center[0], b.box[s].center[1]}, v{b.vx[s], b.vy[s]};
    if (!(ids[k].value == b.id[s] && same(p.x, positions[k].x) && same(p.y, positions[k].y) &&
          same(v.x, velocities[k].x) && same(v.y, velocities[k].y))) {
      ids[k] = BodyId{b.id[s]};
      positions[k] = p;
      velocities[k] = v;
      changed.push_back(k);
    }
    ++k;
  }
}

}  // namespace chain
