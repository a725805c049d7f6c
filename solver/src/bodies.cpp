// SPDX-License-Identifier: MIT
#include "bodies.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <numeric>
#include <tuple>
#include <utility>

namespace chain::detail {
namespace {

// Maps a double to an unsigned key with the same order (and -0 below +0), so that sorting never
// meets two keys that compare equal yet differ in bits.
std::uint64_t order_key(double f) {
  constexpr std::uint64_t kSign = 0x8000000000000000u;
  const auto bits = std::bit_cast<std::uint64_t>(f);
  return (bits & kSign) ? ~bits : (bits | kSign);
}

// Spreads the low 32 bits of v over the even bits of the result.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0xffffffffull;
  v = (v | (v << 16)) & 0x0000ffff0000ffffull;
  v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
  v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
  v = (v | (v << 2)) & 0x3333333333333333ull;
  v = (v | (v << 1)) & 0x5555555555555555ull;
  return v;
}

// Z-order keys of the centres on a grid of about one body size: bodies near each other in space
// get keys near each other, so sorting by them puts neighbours close in memory (a row-major
// order puts the body above another a whole row of bodies away).
std::vector<std::uint64_t> z_order(const Bodies& b) {
  const std::uint32_t n = b.size();
  std::vector<std::uint64_t> keys(n, 0);
  if (n == 0) return keys;
  std::vector<double> sizes(n);
  double x0 = b.x(0), y0 = b.y(0), x1 = x0, y1 = y0;
  for (std::uint32_t i = 0; i < n; ++i) {
    sizes[i] = 2.0 * std::max(b.hx(i), b.hy(i));
    x0 = std::min(x0, b.x(i)), x1 = std::max(x1, b.x(i));
    y0 = std::min(y0, b.y(i)), y1 = std::max(y1, b.y(i));
  }
  std::nth_element(sizes.begin(), sizes.begin() + n / 2, sizes.end());
  // A cell the median body's size, or coarser if the scene is too wide for 32-bit coordinates.
  const double cell =
      std::max({sizes[n / 2], (x1 - x0) * 0x1.0p-31, (y1 - y0) * 0x1.0p-31, 1e-300});
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto qx = static_cast<std::uint64_t>((b.x(i) - x0) / cell);
    const auto qy = static_cast<std::uint64_t>((b.y(i) - y0) / cell);
    keys[i] = spread_bits(qx) | (spread_bits(qy) << 1);
  }
  return keys;
}

int kind_rank(BodyType type) {
  switch (type) {
    case BodyType::kDynamic:
      return 0;
    case BodyType::kKinematic:
      return 1;
    case BodyType::kStatic:
      return 2;
  }
  return 3;
}

// Every field that tells bodies apart, after their kind and place along the Z-order curve: what
// each is now, then what it was created as, then its id (creation order), which only breaks ties
// between bodies created identical and still so.
auto state_fields(const Bodies& b, std::uint32_t i, std::span<const Origin> origin_of_id) {
  const Origin& o = origin_of_id[b.id[i]];
  return std::tuple(order_key(b.y(i)), order_key(b.x(i)), order_key(b.hy(i)), order_key(b.hx(i)),
                    order_key(b.mass[i]), order_key(b.vx[i]), order_key(b.vy[i]),
                    order_key(b.gravity_scale[i]), order_key(b.restitution[i]),
                    order_key(b.friction[i]), b.driven[i], order_key(b.drive_x[i]),
                    order_key(b.drive_y[i]), (b.filter.empty() ? Bodies::kNoFilter : b.filter[i]),
                    order_key(b.surface.empty() ? 0.0 : b.surface[i].x),
                    order_key(b.surface.empty() ? 0.0 : b.surface[i].y), order_key(o.cy),
                    order_key(o.cx), order_key(o.vx), order_key(o.vy), b.id[i]);
}

}  // namespace

Origin origin_of(const BodyDef& def) {
  // Zero velocity for a static body, as append() stores it: a static body's velocity is ignored.
  const bool moves = def.type != BodyType::kStatic;
  return {def.center.x, def.center.y, moves ? def.velocity.x : 0.0, moves ? def.velocity.y : 0.0};
}

void Bodies::append(const BodyDef& def, std::uint32_t body_id) {
  const bool dynamic = def.type == BodyType::kDynamic;
  each_array([](auto& v) { reserve_one_more(v); });
  box.push_back({{def.center.x, def.center.y}, {def.half_extents.x, def.half_extents.y}});
  vx.push_back(def.type == BodyType::kStatic ? 0.0 : def.velocity.x);
  vy.push_back(def.type == BodyType::kStatic ? 0.0 : def.velocity.y);
  mass.push_back(dynamic ? def.mass : 0.0);
  gravity_scale.push_back(dynamic ? def.gravity_scale : 0.0);
  restitution.push_back(def.restitution);
  friction.push_back(def.friction);
  start.push_back({def.center.x, def.center.y});
  drive_x.push_back(0.0);
  drive_y.push_back(0.0);
  driven.push_back(0);
  touching.push_back(TouchBits{});
  type.push_back(def.type);
  id.push_back(body_id);
  const std::uint32_t f = std::uint32_t{def.category_bits} | std::uint32_t{def.mask_bits} << 16;
  if (!filter.empty() || f != kNoFilter) {
    if (filter.empty()) filter.assign(id.size() - 1, kNoFilter);  // the first body that filters
    push_buffer(filter, f);
  }
  const Point s{def.surface_velocity.x, def.surface_velocity.y};
  if (!surface.empty() || s.x != 0.0 || s.y != 0.0) {
    if (surface.empty()) surface.assign(id.size() - 1, Point{0.0, 0.0});
    push_buffer(surface, s);
  }
}

void Bodies::kill(std::uint32_t slot) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  box[slot].center[0] = box[slot].center[1] = kNaN;
  start[slot] = {kNaN, kNaN};
  vx[slot] = vy[slot] = 0.0;
  gravity_scale[slot] = restitution[slot] = friction[slot] = 0.0;
  drive_x[slot] = drive_y[slot] = 0.0;
  driven[slot] = 0;
  touching[slot] = TouchBits{};
  id[slot] = kDeadId;
}

void Bodies::move_slot(std::uint32_t from, std::uint32_t to) {
  each_array([from, to](auto& v) { v[to] = v[from]; });
}

void Bodies::truncate(std::uint32_t n) {
  each_array([n](auto& v) { v.resize(n); });
}

void Bodies::drop_dead() {
  std::uint32_t kept = 0;
  for (std::uint32_t i = 0; i < size(); ++i) {
    if (dead(i)) continue;
    if (kept != i) move_slot(i, kept);
    ++kept;
  }
  truncate(kept);
}

std::uint32_t Bodies::swap_remove(std::uint32_t slot) {
  const std::uint32_t last = size() - 1;
  each_array([slot, last](auto& v) {
    v[slot] = v[last];
    v.pop_back();
  });
  return slot < size() ? id[slot] : kNoSlot;
}

void Bodies::canonicalize(std::vector<std::uint32_t>& slot_of_id,
                          std::span<const Origin> origin_of_id) {
  const std::uint32_t n = size();
  std::vector<std::uint32_t> order(n);
  // Kind first, then place along a Z-order curve; every field that tells bodies apart takes part
  // after that. Two bodies created apart can reach the same state bit for bit (both pushed flush
  // against one wall, say); what each was created as (its first centre and velocity) then decides,
  // so that which one takes which slot never follows the creation order. The id (creation order)
  // breaks only ties between bodies created identical and still so, where the choice cannot
  // matter.
  const std::vector<std::uint64_t> z = z_order(*this);
  auto full_key = [&](std::uint32_t i) {
    return std::tuple_cat(std::tuple(kind_rank(type[i]), z[i]),
                          state_fields(*this, i, origin_of_id));
  };
  // The key's first three fields, which nearly always decide, are sorted together with the slot;
  // the whole key is built only for the pairs they leave tied: the same order as sorting by the
  // whole key, without making two twenty-field tuples at every comparison.
  struct Leading {
    std::uint64_t z, y;
    std::uint32_t kind, slot;
  };
  std::vector<Leading> leading(n);
  for (std::uint32_t i = 0; i < n; ++i)
    leading[i] = {z[i], order_key(y(i)), static_cast<std::uint32_t>(kind_rank(type[i])), i};
  std::sort(leading.begin(), leading.end(), [&](const Leading& a, const Leading& b) {
    if (a.kind != b.kind) return a.kind < b.kind;
    if (a.z != b.z) return a.z < b.z;
    if (a.y != b.y) return a.y < b.y;
    return full_key(a.slot) < full_key(b.slot);
  });
  for (std::uint32_t i = 0; i < n; ++i)
    order[i] = leading[i].slot;

  Spare spare;
  permute(order, spare);

  dynamic_end = movable_end = 0;
  bounces = false;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (type[i] == BodyType::kDynamic) dynamic_end = i + 1;
    if (type[i] != BodyType::kStatic) movable_end = i + 1;
    if (restitution[i] > 0.0) bounces = true;
  }
  for (std::uint32_t i = 0; i < n; ++i)
    slot_of_id[id[i]] = i;
}

void Bodies::sort_by_state(std::span<std::uint32_t> slots,
                           std::span<const Origin> origin_of_id) const {
  auto key = [&](std::uint32_t i) {
    return std::tuple_cat(std::tuple(kind_rank(type[i])), state_fields(*this, i, origin_of_id));
  };
  std::sort(slots.begin(), slots.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
}

void Bodies::permute(std::span<const std::uint32_t> order, Spare& spare) {
  each_array([&](auto& v) { spare.gather(v, order); });
}

}  // namespace chain::detail
