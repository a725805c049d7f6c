#include "tunnelling.h"

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

// Where the segment r0 -> r1 (t in [0, 1]) is inside the open box |x| < h.x, |y| < h.y.
// Returns false when it never is.
bool cross(Vec2d r0, Vec2d r1, Vec2d h, Crossing& c) {
  const double p0[2] = {r0.x, r0.y}, p1[2] = {r1.x, r1.y}, half[2] = {h.x, h.y};
  for (int a = 0; a < 2; ++a) {
    const double d = p1[a] - p0[a];
    if (d == 0.0) {
      if (std::abs(p0[a]) >= half[a]) return false;
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
  return c.enter_t < c.exit_t && c.enter_t < 1.0 && c.exit_t > 0.0;
}

bool inside(Vec2d r, Vec2d h) {
  return std::abs(r.x) < h.x && std::abs(r.y) < h.y;
}

constexpr std::int8_t opposite(std::int8_t face) {
  return static_cast<std::int8_t>(face ^ 1);
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

bool TunnelWatch::deep(std::size_t i, std::size_t j, Vec2d r0, Vec2d r1, int axis) const {
  const Vec2d h{half_[i].x + half_[j].x, half_[i].y + half_[j].y};
  const double a0 = axis == 0 ? r0.x : r0.y, a1 = axis == 0 ? r1.x : r1.y;
  if ((a0 > 0.0) == (a1 > 0.0) && a1 != 0.0) return false;
  const double t = a0 == a1 ? 0.0 : a0 / (a0 - a1);
  const double b0 = axis == 0 ? r0.y : r0.x, b1 = axis == 0 ? r1.y : r1.x;
  const double across = axis == 0 ? h.y : h.x;
  const double smaller =
      axis == 0 ? std::min(half_[i].y, half_[j].y) : std::min(half_[i].x, half_[j].x);
  return std::abs(b0 + t * (b1 - b0)) <= across - smaller;
}

void TunnelWatch::check(const BodyState& before, const BodyState& after, std::size_t i,
                        std::size_t j, int step) {
  const Vec2d h{half_[i].x + half_[j].x, half_[i].y + half_[j].y};
  const Vec2d r0{before.position[i].x - before.position[j].x,
                 before.position[i].y - before.position[j].y};
  const Vec2d r1{after.position[i].x - after.position[j].x,
                 after.position[i].y - after.position[j].y};
  auto deep_crossing = [&](int axis) { return deep(i, j, r0, r1, axis); };
  const std::uint64_t pair = static_cast<std::uint64_t>(i) << 32 | static_cast<std::uint64_t>(j);
  // The pair's entry face and depth flag as locals, not an Inside being filled in: a struct
  // built on the stack field by field and then read whole stalls every call on the store
  // forwarding of its padding.
  std::int8_t entry = kNoFace, exit = kNoFace;
  bool deep_now = false;
  if (inside(r0, h)) {
    if (const Inside* was = find(pair)) entry = was->entry, deep_now = was->deep;
    if (entry != kNoFace) deep_now = deep_now || deep_crossing(entry / 2);
    if (inside(r1, h)) {
      next_.push_back({pair, entry, deep_now});
      return;
    }
    Crossing c;
    if (!cross(r0, r1, h, c)) return;
    exit = c.exit_face;
  } else {
    // A segment whose bounding box misses the open box never enters it, as cross() would find
    // with four divisions: most pairs judged are neighbours resting face to face, or apart.
    if (std::min(r0.x, r1.x) >= h.x || std::max(r0.x, r1.x) <= -h.x ||
        std::min(r0.y, r1.y) >= h.y || std::max(r0.y, r1.y) <= -h.y)
      return;
    Crossing c;
    if (!cross(r0, r1, h, c)) return;
    entry = c.enter_face;
    deep_now = deep_crossing(entry / 2);
    if (inside(r1, h)) {
      next_.push_back({pair, entry, deep_now});
      return;
    }
    exit = c.exit_face;
  }
  if (entry == kNoFace || exit != opposite(entry) || !deep_now) return;
  // The relative centre left through the far face: the body that moved more went through.
  const bool i_moved = std::hypot(after.position[i].x - before.position[i].x,
                                  after.position[i].y - before.position[i].y) >=
                       std::hypot(after.position[j].x - before.position[j].x,
                                  after.position[j].y - before.position[j].y);
  ++count_;
  // Of several in one step, the lowest pair's, whatever order the pairs are judged in.
  if (!first_ || (first_->step == step && pair < first_pair_)) {
    first_ = TunnelEvent{i_moved ? i : j, i_moved ? j : i, step};
    first_pair_ = pair;
  }
}

// What check() does to a pair that did not move: one outside stays out, one inside stays in and
// is judged again for having crossed the middle, at the point it rests on.
void TunnelWatch::rest(const BodyState& s, Inside& p) const {
  if (p.entry == kNoFace || p.deep) return;
  const auto i = static_cast<std::size_t>(p.pair >> 32);
  const auto j = static_cast<std::size_t>(p.pair & 0xffffffffu);
  const Vec2d r{s.position[i].x - s.position[j].x, s.position[i].y - s.position[j].y};
  p.deep = deep(i, j, r, r, p.entry / 2);
}

void TunnelWatch::hold(const BodyState& s) {
  // At rest a second time, each pair is judged at the point it was judged at already.
  if (held_) return;
  for (Inside& p : inside_)
    rest(s, p);
  held_ = true;
}

void TunnelWatch::carry(const BodyState& s, std::span<const std::uint8_t> moved) {
  for (const Inside& p : inside_) {
    if (moved[p.pair >> 32] || moved[p.pair & 0xffffffffu]) continue;
    next_.push_back(p);
    rest(s, next_.back());
  }
}

void TunnelWatch::end_step() {
  held_ = false;
  // No figure depends on the order of inside_: first() is the lowest pair of its step, and
  // every other use of a pair is its own.
  inside_.swap(next_);
  next_.clear();
  index();
}

}  // namespace chainbench
