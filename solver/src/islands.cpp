// SPDX-License-Identifier: MIT
#include "islands.h"

#include "buffer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numeric>

namespace chain::detail {
namespace {

// Where the step began it, at velocity +0, in bits (as rest.h asks of the whole world).
bool at_rest(const Bodies& b, std::uint32_t i) {
  return std::memcmp(b.box[i].center, &b.start[i], sizeof(Point)) == 0 &&
         std::bit_cast<std::uint64_t>(b.vx[i]) == 0 && std::bit_cast<std::uint64_t>(b.vy[i]) == 0;
}

}  // namespace

void Islands::reset(std::uint32_t slots) {
  assign_buffer(far_, slots, 0.0);
  assign_buffer(skipped_, slots, std::uint8_t{0});
  assign_buffer(flags_, slots, std::uint8_t{0});
  assign_buffer(spent_, slots, 0u);
  resize_buffer(next_, slots);
  std::iota(next_.begin(), next_.end(), 0u);
  runs_.clear();
  solved_.clear();
  run_count_ = solved_count_ = 0;
  saved_v_.clear();
  kept_.clear();
  changed_.clear();
  to_wake_.clear();
  woke_ = false;
  skipped_spend_ = 0;
  skipped_count_ = 0;
  planned_ = false;
  tracking_ = true;
  counted_last_ = false;
  backoff_ = wait_ = unpaid_ = 0;
}

void Islands::wake_island(std::uint32_t s) {
  std::uint32_t m = s;
  do {
    const std::uint32_t after = next_[m];
    if (skipped_[m]) {
      skipped_[m] = 0;
      skipped_spend_ -= spent_[m];
      --skipped_count_;
      woke_ = true;
    }
    spent_[m] = 0;
    next_[m] = m;
    m = after;
  } while (m != s);
}

void Islands::wake(std::uint32_t s) {
  if (s >= next_.size()) return;  // created since the last step: no island yet
  wake_island(s);
  flags_[s] = 0;
  push_buffer(changed_, s);
}

// Dead slots (Bodies::kill) come too: their centres and starts are NaN, so they are never at
// rest and never near anything.
template <class Fn>
void Islands::each_solved(const Bodies& b, Fn&& fn) const {
  if (planned_) {
    for (const std::uint32_t i : solved())
      fn(i);
    return;
  }
  for (std::uint32_t i = 0; i < b.movable_end; ++i)
    fn(i);
}

bool Islands::plan(const Bodies& b, const Broadphase& bp, Vec2 gravity, double dt, double tolerance,
                   bool whole) {
  planned_ = false;
  if (skipped_count_ == 0) {
    tracking_ = wait_ == 0;
    changed_.clear();
    return false;
  }
  tracking_ = true;
  if (whole || !bp.built() ||
      std::bit_cast<std::uint64_t>(dt) != std::bit_cast<std::uint64_t>(dt_)) {
    for (std::uint32_t i = 0; i < b.movable_end; ++i) {
      if (skipped_[i]) wake_island(i);
    }
    changed_.clear();
    return false;
  }
  // The islands a moving body may reach next step are woken after the step (settle()); a body
  // the API changed since, or just created, wakes those it may reach on its way now: its box on
  // the way its integrated velocity takes it, grown by that move again (what it pushes moves
  // about as far). A guess: an island it misses is found after the step, solved again whole.
  const double touch = kMargin + 2.0 * tolerance;
  for (const std::uint32_t i : changed_) {
    if (!guess_ || i >= b.movable_end || skipped_[i] || b.dead(i)) continue;
    const Vec2 v = integrated_velocity(b, i, gravity, dt);
    const double dx = v.x * dt, dy = v.y * dt, move = std::max(std::abs(dx), std::abs(dy));
    const Box way{b.x(i) + 0.5 * dx, b.y(i) + 0.5 * dy, b.hx(i) + 0.5 * std::abs(dx),
                  b.hy(i) + 0.5 * std::abs(dy)};
    const double pad = touch + cap_of(bp) + move;
    bp.for_each_in_box(b, way.x, way.y, way.hx, way.hy, pad + cap_of(bp), [&](std::uint32_t j) {
      if (j < b.movable_end && skipped_[j] && near(way, held_box(b, j), pad)) wake_island(j);
    });
  }
  changed_.clear();
  if (skipped_count_ == 0) return false;
  // The solved slots one by one, then their runs, with no branch on each slot's flag: a loop
  // that stops where the flags change mispredicts at every change, and they change thousands of
  // times a step where bodies rest among moving ones. Eight flags at once where all are left out.
  const std::uint32_t n = b.movable_end;
  auto eight = [&](std::uint32_t i) {
    std::uint64_t w;
    std::memcpy(&w, skipped_.data() + i, sizeof w);
    return w;
  };
  constexpr std::uint64_t kAllSkipped = 0x0101010101010101ull;
  if (solved_.size() < n) resize_buffer(solved_, n);  // sized once: resize() would write n zeros
  std::uint32_t k = 0, i = 0;
  for (; i + 8 <= n; i += 8) {
    if (eight(i) == kAllSkipped) continue;
    for (std::uint32_t t = 0; t < 8; ++t) {
      solved_[k] = i + t;  // kept when the slot is solved
      k += skipped_[i + t] ^ 1u;
    }
  }
  for (; i < n; ++i) {
    solved_[k] = i;
    k += skipped_[i] ^ 1u;
  }
  solved_count_ = k;
  if (runs_.size() < n) resize_buffer(runs_, n);
  std::uint32_t r = 0;
  if (k > 0) runs_[r++] = {solved_[0], solved_[0] + 1};
  for (std::uint32_t q = 1; q < k; ++q) {
    const std::uint32_t slot = solved_[q];
    // All ones where the slot begins a run: the begin is taken from it by a mask, not a branch.
    const std::uint32_t fresh = 0u - static_cast<std::uint32_t>(slot != runs_[r - 1].end);
    r += fresh & 1u;
    runs_[r - 1].begin = (slot & fresh) | (runs_[r - 1].begin & ~fresh);
    runs_[r - 1].end = slot + 1;
  }
  run_count_ = r;
  planned_ = true;
  return true;
}

void Islands::save(const Bodies& b) {
  resize_buffer(saved_v_, solved_count_);
  for (std::size_t k = 0; k < solved_count_; ++k)
    saved_v_[k] = {b.vx[solved_[k]], b.vy[solved_[k]]};
}

void Islands::undo(Bodies& b) {
  for (std::uint32_t i = 0; i < b.movable_end; ++i) {
    b.box[i].center[0] = b.start[i].x;
    b.box[i].center[1] = b.start[i].y;
    if (skipped_[i]) {
      b.vx[i] = b.vy[i] = 0.0;
      skipped_[i] = 0;
      next_[i] = i;
    }
  }
  for (std::size_t k = 0; k < solved_count_; ++k) {
    b.vx[solved_[k]] = saved_v_[k].x;
    b.vy[solved_[k]] = saved_v_[k].y;
  }
  std::fill(spent_.begin(), spent_.end(), 0u);
  woke_ = true;
  skipped_spend_ = 0;
  skipped_count_ = 0;
  planned_ = false;
  reach_.moved_skipped = false;
}

Reach* Islands::begin_reach(const Bodies& b) {
  if (!tracking_) return nullptr;
  reach_.start = b.start.data();
  reach_.far = far_.data();
  reach_.skipped = planned_ ? skipped_.data() : nullptr;
  reach_.moved_skipped = false;
  touches_.clear();
  reach_.touches = &touches_;
  each_solved(b, [&](std::uint32_t i) {
    far_[i] = std::max(std::abs(b.x(i) - b.start[i].x), std::abs(b.y(i) - b.start[i].y));
  });
  return &reach_;
}

std::uint32_t Islands::find(std::uint32_t i) {
  while (next_[i] != i) {
    next_[i] = next_[next_[i]];
    i = next_[i];
  }
  return i;
}

bool Islands::settle(const Bodies& b, const Broadphase& bp, const ChainResolver& resolver,
                     std::span<const std::uint32_t> fast, std::span<const CrushRecord> crushed,
                     bool cut, Vec2 gravity, double dt, double tolerance) {
  if (!tracking_) {
    if (wait_ > 0) --wait_;
    counted_last_ = false;
    return true;
  }
  if (planned_ && (cut || reach_.moved_skipped || !bp.built())) return false;
  // Which solved bodies came out at rest, having gone no farther than the broadphase's refile
  // distance on the way: the reach every query below allows a body at rest.
  const double cap = cap_of(bp);
  std::uint32_t solved = 0, resting = 0;
  // The farthest any solved body went, of those that went at most kFarShare refile distances
  // (the others find their own neighbours below), and at least the refile distance (what a
  // left-out body went when last solved).
  double far_off = cap;
  std::uint64_t rest_spend = 0;  // what the bodies at rest resolved this step
  each_solved(b, [&](std::uint32_t i) {
    const bool rests =
        !cut && far_[i] <= cap && at_rest(b, i) && !b.dead(i) && !resolver.squeezed_lately(i);
    flags_[i] = static_cast<std::uint8_t>((flags_[i] & kStillMask) | (rests ? kRests : 0));
    ++solved;
    resting += rests ? 1 : 0;
    rest_spend += rests ? spent_[i] : 0;
    if (far_[i] > far_off && far_[i] <= kFarShare * cap) far_off = far_[i];
  });
  auto moved = [&](std::uint32_t i) {
    if (flags_[i] & kRests) --resting;
    flags_[i] &= static_cast<std::uint8_t>(~kRests);
  };
  for (const std::uint32_t f : fast)
    moved(f);
  for (const CrushRecord& c : crushed)
    moved(c.body);
  auto file_still = [&](std::uint32_t i) {
    const std::uint8_t f = flags_[i];
    const std::uint8_t still = !(f & kRests) ? 0
                               : counted_last_
                                   ? std::min<std::uint8_t>((f & kStillMask) + 1, kRested)
                                   : 1;
    flags_[i] = static_cast<std::uint8_t>((f & ~kStillMask) | still);
  };
  // A step that searches for no island files only the still counts, and, after `waited`
  // (non-null) doubles, looks again that many steps later.
  auto no_search = [&](std::uint32_t* waited) {
    each_solved(b, [&](std::uint32_t i) {
      file_still(i);
      spent_[i] = 0;
    });
    if (waited != nullptr) {
      *waited = std::min(2 * *waited + 1, kMaxWait);
      wait_ = *waited;
    }
    counted_last_ = true;
    dt_ = dt;
    return true;
  };
  // Too little at rest to look for islands: look again later, less often the longer it moves.
  if (!planned_ && (resting == 0 || 4 * resting < solved)) return no_search(&backoff_);
  backoff_ = 0;
  // The first step looked at after a wait: no body has come out of two looked-at steps at rest
  // yet, so no island can form.
  if (!planned_ && !counted_last_) return no_search(nullptr);
  // Were every body at rest left out, what they resolved would still not pay (below): islands
  // are looked for later, as when they do not pay.
  if (weigh_ && !planned_ && !pays(rest_spend, solved - resting)) return no_search(&unpaid_);
  // Islands: the bodies at rest whose reach came within a touch of each other's, joined (next_ as
  // the union-find parent: solved bodies are in no island). One that a moving body came near
  // enough to reach next step is open; a left-out body that a solved one came within a touch of
  // means the step was not what it would have been, and one a moving body may reach next step
  // wakes. The pairs that may have come a touch apart are near pairs (ChainResolver::near), but
  // for bodies filed again since the scan, and bodies that went far: those are queried.
  const double touch = kMargin + 2.0 * tolerance;
  const bool lists = resolver.near_lists_serve(bp) && touch < 2.0 * bp.refile_distance();
  bool met = false;
  to_wake_.clear();
  // Where a moving body may go next step: its box now and where its velocity takes it in dt,
  // grown by what a step's gravity adds, and by the refile distance for what it pushes.
  auto ahead = [&](std::uint32_t m) {
    const double dx = b.vx[m] * dt, dy = b.vy[m] * dt;
    const double g = (std::abs(gravity.x) + std::abs(gravity.y)) *
                         (m < b.dynamic_end ? std::abs(b.gravity_scale[m]) : 0.0) * dt * dt +
                     cap;
    return Box{b.x(m) + 0.5 * dx, b.y(m) + 0.5 * dy, b.hx(m) + 0.5 * std::abs(dx) + g,
               b.hy(m) + 0.5 * std::abs(dy) + g};
  };
  auto pair = [&](std::uint32_t i, std::uint32_t j) {  // i solved
    if (j == i || j >= b.movable_end) return;
    const bool sj = skipped_[j] != 0, ri = (flags_[i] & kRests) != 0;
    const bool rj = !sj && (flags_[j] & kRests) != 0;
    if (!sj && !ri && !rj) return;  // two moving bodies: nothing to learn
    if (b.dead(j)) return;
    const Box bi = held_box(b, i), bj = held_box(b, j);
    if (sj) {
      if (near(bi, bj, touch)) {
        met = true;
      } else if (guess_ && !ri && near(ahead(i), bj, touch)) {
        push_buffer(to_wake_, j);
      }
    } else if (ri && rj) {
      if (near(bi, bj, touch)) {
        const std::uint32_t a = find(i), c = find(j);
        if (a != c) next_[std::max(a, c)] = std::min(a, c);
      }
    } else {
      // A body at rest that a moving one met this step, or may meet the next, stays solved.
      const std::uint32_t r = ri ? i : j, m = ri ? j : i;
      if (near(bi, bj, touch) || near(ahead(m), held_box(b, r), touch)) flags_[r] |= kOpen;
    }
  };
  // The bodies that came near one, found where they are now: each went at most far_off, so its
  // box then is within twice that of its box now.
  auto query = [&](std::uint32_t i, double slack) {
    const Box r = held_box(b, i);
    bp.for_each_in_box(b, r.x, r.y, r.hx, r.hy, slack, [&](std::uint32_t j) {
      if (skipped_[i]) {
        if (!skipped_[j]) pair(j, i);
      } else {
        pair(i, j);
      }
    });
  };
  each_solved(b, [&](std::uint32_t i) {
    if (!lists || bp.stale(i)) {
      query(i, touch + 2.0 * far_off);
      return;
    }
    // One that went farther meets bodies not in its list: those at rest or left out matter.
    if (far_[i] > far_off) query(i, touch + 2.0 * cap);
    const bool ri = (flags_[i] & kRests) != 0;
    for (const std::uint32_t e : resolver.near(i)) {
      const std::uint32_t j = ChainState::entry_slot(e);
      // Solved pairs once, at the later body, and only where one of the two is at rest. Static
      // bodies (slots from movable_end) are neither left out nor at rest, and come after i: the
      // test, in bit operations, is one branch an entry.
      const unsigned later = j < i ? 1u : 0u, rj = (flags_[j] & kRests) != 0 ? 1u : 0u;
      if ((skipped_[j] | (later & (static_cast<unsigned>(ri) | rj))) != 0) pair(i, j);
    }
  });
  // A left-out body filed again since the scan is missing from its neighbours' near lists.
  if (lists) {
    bp.for_each_stale([&](std::uint32_t k) {
      if (k < b.movable_end && skipped_[k]) query(k, touch + 2.0 * far_off);
    });
  }
  if (met) {
    each_solved(b, [&](std::uint32_t i) { next_[i] = i; });
    return false;
  }
  for (const std::uint32_t j : to_wake_) {
    if (skipped_[j]) wake_island(j);
  }
  // An island is left out from the next step on when every body of it came out of two solved
  // steps in a row at rest and none came near a body that did not.
  each_solved(b, [&](std::uint32_t i) {
    file_still(i);
    if (still(i) < kRested || (flags_[i] & kOpen)) flags_[find(i)] |= kOpen;
  });
  // The left-out bodies' pushes against static bodies, for touch_statics(): those of bodies woken
  // since go first, so that a body left out again counts only its last solve's.
  if (woke_) {
    std::erase_if(kept_, [&](const StaticTouch& t) { return !skipped_[t.body]; });
    woke_ = false;
  }
  // Each parent pointer made the root itself; then each member of an island left out joins its
  // root's ring, and the others point at themselves.
  each_solved(b, [&](std::uint32_t i) {
    const std::uint32_t r = find(i);
    if (r == i) flags_[i] |= kRoot;
    next_[i] = r;
  });
  each_solved(b, [&](std::uint32_t i) {
    const std::uint32_t r = (flags_[i] & kRoot) ? i : next_[i];
    if (flags_[r] & kOpen) {
      next_[i] = i;
      spent_[i] = 0;
      return;
    }
    skipped_[i] = 1;
    ++skipped_count_;
    skipped_spend_ += spent_[i];
    if (r != i) {
      next_[i] = next_[r];
      next_[r] = i;
    }
  });
  // Leaving islands out pays for the checks above (about a pass over every solved body's near
  // list) only where what it leaves out would resolve something: an island that touches nothing
  // saves its integration alone. Where the left-out bodies took less of the budget when last
  // solved (spent_: pair resolutions and charges) than half the bodies solved, every island is
  // solved from the next step on, and islands are looked for again later, less often the longer
  // leaving them out does not pay.
  if (weigh_ && skipped_count_ > 0 && !pays(skipped_spend_, b.movable_end - skipped_count_)) {
    for (std::uint32_t i = 0; i < b.movable_end; ++i) {
      if (skipped_[i]) wake_island(i);
    }
    unpaid_ = std::min(2 * unpaid_ + 1, kMaxWait);
    wait_ = unpaid_;
  } else if (skipped_count_ > 0) {
    unpaid_ = 0;
  }
  for (const StaticTouch& t : touches_) {
    if (skipped_[t.body]) push_buffer(kept_, t);  // left out from the next step on
  }
  counted_last_ = true;
  planned_ = false;
  dt_ = dt;
  return true;
}

void Islands::touch_statics(Bodies& b) {
  for (const StaticTouch& t : kept_) {
    if (skipped_[t.body]) add_touch(b.touching[t.wall], t.side);
  }
}

}  // namespace chain::detail
