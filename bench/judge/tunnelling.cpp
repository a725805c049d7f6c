// SPDX-License-Identifier: MIT
#include "judge/tunnelling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace chainbench {
namespace {

struct Crossing {
  double enter_t = -std::numeric_limits<double>::infinity();
  double exit_t = std::numeric_limits<double>::infinity();
  std::int8_t enter_face = -1, exit_face = -1;
};

// Where the segment r0 -> r1 (t in [0, 1]) is in the closed box |x| <= h.x, |y| <= h.y, over a
// stretch of some length: a segment that only touches a corner is never in it. Returns false
// when it never is.
bool cross(Vec2d r0, Vec2d r1, Vec2d h, Crossing& c) {
  const double p0[2] = {r0.x, r0.y}, p1[2] = {r1.x, r1.y}, half[2] = {h.x, h.y};
  for (int a = 0; a < 2; ++a) {
    const double d = p1[a] - p0[a];
    if (d == 0.0) {
      if (std::abs(p0[a]) > half[a]) return false;
      continue;
    }
    // Moving towards +: enters through the negative face, leaves through the positive one.
    const double t_neg = (-half[a] - p0[a]) / d, t_pos = (half[a] - p0[a]) / d;
    const double t_in = std::min(t_neg, t_pos), t_out = std::max(t_neg, t_pos);
    const auto in_face = static_cast<std::int8_t>(2 * a + (d > 0.0 ? 0 : 1));
    const auto out_face = static_cast<std::int8_t>(2 * a + (d > 0.0 ? 1 : 0));
    if (t_in > c.enter_t) c.enter_t = t_in, c.enter_face = in_face;
    if (t_out < c.exit_t) c.exit_t = t_out, c.exit_face = out_face;
  }
  return c.enter_t < c.exit_t && c.enter_t <= 1.0 && c.exit_t >= 0.0;
}

bool inside(Vec2d r, Vec2d h) {
  return std::abs(r.x) <= h.x && std::abs(r.y) <= h.y;
}

// What a centre lying on a face may be off it by in rounding: the two centres' difference and a
// face built as centre + half extent are each a few units in the last place of the coordinates.
double rounding(Vec2d a0, Vec2d a1, Vec2d b0, Vec2d b1) {
  const double m = std::max({std::abs(a0.x), std::abs(a0.y), std::abs(a1.x), std::abs(a1.y),
                             std::abs(b0.x), std::abs(b0.y), std::abs(b1.x), std::abs(b1.y)});
  return 8.0 * std::numeric_limits<double>::epsilon() * m;
}

}  // namespace

TunnelWatch::TunnelWatch(const Scene& scene) {
  for (const SceneBody& b : scene.bodies) {
    if (!scene.rotation) {
      half_.push_back(b.half_extents);
    } else {
      const double inscribed = std::min(b.half_extents.x, b.half_extents.y) / std::sqrt(2.0);
      half_.push_back({inscribed, inscribed});
    }
  }
}

const TunnelWatch::Inside* TunnelWatch::find(std::uint64_t pair) const {
  if (inside_.empty()) return nullptr;
  for (std::size_t k = home(pair);; k = (k + 1) & (index_.size() - 1)) {
    const std::uint32_t at = index_[k];
    if (at == 0) return nullptr;
    if (inside_[at - 1].pair == pair) return &inside_[at - 1];
  }
}

void TunnelWatch::index() {
  const std::size_t size = std::bit_ceil(std::max<std::size_t>(16, 2 * inside_.size()));
  index_.assign(size, 0);
  for (std::size_t at = 0; at < inside_.size(); ++at) {
    std::size_t k = home(inside_[at].pair);
    while (index_[k] != 0)
      k = (k + 1) & (size - 1);
    index_[k] = static_cast<std::uint32_t>(at + 1);
  }
}

bool TunnelWatch::follow(Vec2d r0, Vec2d r1, Vec2d h, std::int8_t& entry) {
  const bool in0 = inside(r0, h), in1 = inside(r1, h);
  if (in0 && in1) {
    if (entry == kOut) entry = kNoFace;  // inside with no record: it started there
    return false;
  }
  Crossing c;
  if (!cross(r0, r1, h, c)) {
    entry = kOut;
    return false;
  }
  if (!in0) {
    entry = c.enter_face;
    if (in1) return false;
  } else if (entry == kOut) {
    entry = kNoFace;
  }
  const bool through = entry != kNoFace && c.exit_face != entry;
  entry = kOut;
  return through;
}

void TunnelWatch::check(const BodyState& before, const BodyState& after, std::size_t i,
                        std::size_t j, int step) {
  const Vec2d a0 = before.position[i], a1 = after.position[i];
  const Vec2d b0 = before.position[j], b1 = after.position[j];
  const Vec2d r0{a0.x - b0.x, a0.y - b0.y}, r1{a1.x - b1.x, a1.y - b1.y};
  const double slack = rounding(a0, a1, b0, b1);
  // i's centre against j's box, j's against i's (the same box about the relative centre, as
  // both are symmetric), each grown by rounding.
  const Vec2d hj{half_[j].x + slack, half_[j].y + slack};
  const Vec2d hi{half_[i].x + slack, half_[i].y + slack};
  // A segment whose bounding box misses both boxes is in neither, as cross() would find with
  // four divisions: most pairs judged are neighbours resting face to face, or apart.
  const double hx = std::max(hj.x, hi.x), hy = std::max(hj.y, hi.y);
  if (std::min(r0.x, r1.x) > hx || std::max(r0.x, r1.x) < -hx || std::min(r0.y, r1.y) > hy ||
      std::max(r0.y, r1.y) < -hy)
    return;
  const std::uint64_t pair = static_cast<std::uint64_t>(i) << 32 | static_cast<std::uint64_t>(j);
  // The record as locals, not an Inside being filled in: a struct built on the stack field by
  // field and then read whole stalls every call on the store forwarding of its padding.
  std::int8_t in_j = kOut, in_i = kOut;
  bool counted = false;
  if (const Inside* was = find(pair)) in_j = was->in_j, in_i = was->in_i, counted = was->counted;
  const bool through_j = follow(r0, r1, hj, in_j);
  const bool through_i = follow(r0, r1, hi, in_i);
  const bool still = in_j != kOut || in_i != kOut;
  if ((through_j || through_i) && !counted) {
    // The body that moved more went through the other.
    const bool i_moved =
        std::hypot(a1.x - a0.x, a1.y - a0.y) >= std::hypot(b1.x - b0.x, b1.y - b0.y);
    ++count_;
    // Of several in one step, the lowest pair's, whatever order the pairs are judged in.
    if (!first_ || (first_->step == step && pair < first_pair_)) {
      first_ = TunnelEvent{i_moved ? i : j, i_moved ? j : i, step};
      first_pair_ = pair;
    }
    counted = true;
  }
  if (still) next_.push_back({pair, in_j, in_i, counted});
}

void TunnelWatch::hold(const BodyState&) {
  // A step that moved nothing leaves every pair where it was: inside_ stands as it is.
}

void TunnelWatch::carry(const BodyState&, std::span<const std::uint8_t> moved) {
  for (const Inside& p : inside_) {
    if (moved[p.pair >> 32] || moved[p.pair & 0xffffffffu]) continue;
    next_.push_back(p);
  }
}

void TunnelWatch::end_step() {
  // No figure depends on the order of inside_: first() is the lowest pair of its step, and
  // every other use of a pair is its own.
  inside_.swap(next_);
  next_.clear();
  index();
}

}  // namespace chainbench
