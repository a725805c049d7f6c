// SPDX-License-Identifier: MIT
// The modern resolver's contacts: finding the overlapping pairs of a pass, and the order they
// are resolved in (shock propagation outward from immovable bodies; each body's immovable contacts
// in the order it entered them).
#include "chain_resolver.h"

#include "box_overlap.h"
#include "buffer.h"
#include "entry_face.h"

#include <algorithm>
#include <cmath>

namespace chain::detail {
namespace {

constexpr std::uint32_t kUnreached = 0xffffffffu;

}  // namespace

// A grid scan gives the near pairs (closer than the slack), which chains look through instead of
// the grid. Every pair of bodies that both stayed within the broadphase's refile distance (a
// quarter of the slack) of where the scan saw them is among them; a body that moved further (a
// fast body, a far push) was filed again and is looked up in the broadphase itself. So the near
// pairs serve from step to step, however far a few bodies went, and are scanned again only when
// the grid changes, a good share of the bodies were filed again, or some body was and the
// broadphase has examined as many candidates since the scan as the scan (and the build before it)
// cost: then a new scan, after which none is stale, pays for itself (the rent-or-buy rule, at most
// twice the work of the best choice made knowing the future; the count takes every query, the
// pass's too, which a scan does not save: an upper bound on what the stale bodies cost). A
// resting pile with one fast body in it neither rebuilds its grid nor rescans its pairs.
// Kept out of gather_contacts' loop over every body, which it would slow by a tenth.
[[gnu::noinline]] void ChainResolver::add_refiled_pairs(const StepContext& ctx, std::uint32_t i,
                                                        std::vector<Pair>& out) const {
  const Bodies& bodies = ctx.bodies;
  const Broadphase& bp = ctx.broadphase;
  const bool filters = !bodies.filter.empty();  // read once, not after every push
  bp.for_each_overlap(bodies, i, ctx.def.touch_tolerance, [&](std::uint32_t j) {
    if ((j < i || !bp.stale(j)) && !(bodies.immovable(i) && bodies.immovable(j)) &&
        (!filters || bodies.collides(i, j)))
      push_buffer(out, {std::min(i, j), std::max(i, j)});
  });
}

void ChainResolver::gather_contacts(StepContext& ctx) {
  const Bodies& bodies = ctx.bodies;
  const double tol = ctx.def.touch_tolerance;
  const Broadphase& bp = ctx.broadphase;
  if (!fresh_grid_ && !rescan_every_step_ && near_generation_ == bp.generation() &&
      bp.stale_count() <= bodies.size() / kRescanShare &&
      (bp.stale_count() == 0 || bp.examined() - examined_after_scan_ <= scan_cost_)) {
    state_.begin_pass(bodies, nullptr);
    if (bp.stale_count() > 0) ++reuses_with_refiled_;
  } else {
    ++scans_;
    const std::uint64_t before = bp.examined();
    if (!fresh_grid_) ctx.broadphase.build(bodies, ctx.dt, ctx.def.gravity);
    fresh_grid_ = false;
    near_generation_ = bp.generation();
    near_pairs_.clear();
    const bool filters = !bodies.filter.empty();
    ctx.broadphase.for_each_near_pair(bodies, [&](std::uint32_t i, std::uint32_t j) {
      if (!filters || bodies.collides(i, j)) push_buffer(near_pairs_, {i, j});  // else no contact
    });
    state_.begin_pass(bodies, &near_pairs_);
    examined_after_scan_ = bp.examined();
    scan_cost_ = examined_after_scan_ - before + bodies.size();
  }
  // Walked body by body in solve order, each pair taken at its later body: the earlier one was
  // just read and is still in cache, and the contacts come out in an order that depends on the
  // bodies alone. A body filed again since the scan takes its pairs from the broadphase (those
  // with another such body at the later one), is skipped in near lists, and its pairs are merged
  // in afterwards (below).
  contacts_.clear();
  const Bodies::Box* const box = bodies.box.data();
  const OverlapTest test(tol);
  if (bp.near_pairs_hold()) {
    const std::uint32_t n = bodies.size();
    // The walks below write at most an entry each into near_pairs_ (the near lists were made from
    // it, and it is not read again until the next scan refills it).
    if (near_pairs_.size() < state_.lower_offset(n))
      resize_buffer(near_pairs_, state_.lower_offset(n));
    // With workers: bodies [begin, end) write their contacts to `out`, at most one per entry. A
    // body the step leaves out (islands.h) resolves nothing: its list is not read.
    const std::uint8_t* const skipped = ctx.skipped;
    auto scan = [&](std::uint32_t begin, std::uint32_t end, Pair* out) {
      Pair* o = out;
      for (std::uint32_t i = begin; i < end; ++i) {
        if (skipped != nullptr && skipped[i]) continue;
        for_each_hit(box, i, state_.lower(i), test, [&o, i](std::uint32_t j) { *o++ = {j, i}; });
      }
      return static_cast<std::uint32_t>(o - out);
    };
    if (ctx.pool.threads() == 1 || n <= kBlock) {
      // Into near_pairs_, then copied: pushed back one by one, the walk kept its constants on the
      // stack for the growing path's call and reloaded them at every body.
      const std::uint32_t found = scan(0, n, near_pairs_.data());
      reserve_buffer(contacts_, found);
      contacts_.assign(near_pairs_.begin(), near_pairs_.begin() + found);
      return;
    }
    // Blocks of bodies at once, each into its own stretch of near_pairs_ (as long as its lower
    // lists), then joined in block order: slot order, as one thread.
    const std::uint32_t blocks = (n + kBlock - 1) / kBlock;
    block_found_.resize(blocks);
    ctx.pool.run(blocks, [&](std::uint32_t k) {
      const std::uint32_t begin = k * kBlock, end = std::min(n, begin + kBlock);
      block_found_[k] = scan(begin, end, near_pairs_.data() + state_.lower_offset(begin));
    });
    for (std::uint32_t k = 0; k < blocks; ++k) {
      const auto from = near_pairs_.begin() + state_.lower_offset(k * kBlock);
      reserve_buffer(contacts_, contacts_.size() + block_found_[k]);
      contacts_.insert(contacts_.end(), from, from + block_found_[k]);
    }
    return;
  }
  // The contacts come out ordered by their later body, then their earlier one, as a scan with no
  // body filed again since would give them: those of the bodies filed again are found apart and
  // merged in, so which bodies were filed again, and when, changes no result.
  // near_pairs_ holds them: no scan ran in this call (a scan leaves no body stale), and nothing
  // reads it again until the next scan refills it; it has room for as many pairs as that scan
  // found, and grows (once) where more were filed again.
  std::vector<Pair>& refiled_pairs = near_pairs_;
  refiled_pairs.clear();
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    if (ctx.skipped != nullptr && ctx.skipped[i]) continue;
    if (bp.stale(i)) {
      add_refiled_pairs(ctx, i, refiled_pairs);
      continue;
    }
    // Its lower near bodies (those of its near list, in slot order) that it overlaps, less the
    // bodies filed again since the scan, which take the pair at their own turn.
    for_each_hit(box, i, state_.lower(i), test, [&](std::uint32_t j) {
      if (!bp.stale(j)) push_buffer(contacts_, {j, i});
    });
  }
  if (refiled_pairs.empty()) return;
  auto later_first = [](const Pair& p, const Pair& q) {
    return p.b != q.b ? p.b < q.b : p.a < q.a;
  };
  std::sort(refiled_pairs.begin(), refiled_pairs.end(), later_first);
  // Merged in place from the back: the refiled bodies' pairs are few, and a second list of every
  // contact would hold as many bytes again.
  std::size_t from = contacts_.size(), refiled = refiled_pairs.size();
  resize_buffer(contacts_, from + refiled);
  for (std::size_t to = from + refiled; refiled > 0;) {
    if (from > 0 && later_first(refiled_pairs[refiled - 1], contacts_[from - 1])) {
      contacts_[--to] = contacts_[--from];
    } else {
      contacts_[--to] = refiled_pairs[--refiled];
    }
  }
}

// A later pass can only find the overlaps the last one's chains left behind, and those flagged
// the bodies involved: the contacts are among the overlaps of those bodies.
void ChainResolver::gather_suspect_contacts(StepContext& ctx) {
  const Broadphase& bp = ctx.broadphase;
  if (fresh_grid_ || near_generation_ != bp.generation()) {
    near_generation_ = kNotScanned;  // forces a new scan
    gather_contacts(ctx);
    return;
  }
  const Bodies& bodies = ctx.bodies;
  contacts_.clear();
  for (const std::uint32_t i : state_.suspects()) {
    found_.clear();
    state_.gather_overlaps(ctx, i, found_);
    for (const std::uint32_t j : found_) {
      if (state_.suspect(j) && j < i) continue;  // both flagged: the pair is taken once
      if (bodies.immovable(i) && bodies.immovable(j)) continue;
      push_buffer(contacts_, {std::min(i, j), std::max(i, j)});
    }
  }
  state_.begin_pass(bodies, nullptr);
}

// Levels: immovable bodies 0, dynamic bodies their contact-graph distance from one (breadth
// first), unreached last. Contacts are stably sorted by the lower level of their two bodies, and
// a dynamic pair is oriented so that `a` is the body nearer to the immovable ones.
void ChainResolver::order_contacts(StepContext& ctx) {
  const Bodies& bodies = ctx.bodies;
  // Number the dynamic bodies the contacts touch: the work is in proportion to the contacts, not
  // to the world.
  if (local_.size() != bodies.size()) {
    assign_buffer(local_, bodies.size(), 0);
    assign_buffer(local_mark_, bodies.size(), 0);
    mark_ = 0;
  }
  if (++mark_ == 0) {
    std::fill(local_mark_.begin(), local_mark_.end(), 0u);
    mark_ = 1;
  }
  involved_.clear();
  auto local = [&](std::uint32_t body) {
    if (local_mark_[body] != mark_) {
      local_mark_[body] = mark_;
      local_[body] = static_cast<std::uint32_t>(involved_.size());
      involved_.push_back(body);
    }
    return local_[body];
  };
  for (const Pair& c : contacts_) {
    local(c.a);  // c.a < c.b and dynamic slots come first: c.a is dynamic
    if (!bodies.immovable(c.b)) local(c.b);
  }
  const auto m = static_cast<std::uint32_t>(involved_.size());
  level_.assign(m, kUnreached);
  adj_start_.assign(m + 2, 0);
  queue_.clear();
  repeat_immovable_ = false;
  for (const Pair& c : contacts_) {
    const std::uint32_t a = local_[c.a];
    if (bodies.immovable(c.b)) {
      if (level_[a] == kUnreached) {
        level_[a] = 1;
        queue_.push_back(a);
      } else {
        repeat_immovable_ = true;
      }
    } else {
      ++adj_start_[a + 2];
      ++adj_start_[local_[c.b] + 2];
    }
  }
  for (std::uint32_t i = 2; i < m + 2; ++i)
    adj_start_[i] += adj_start_[i - 1];
  resize_buffer(adj_, adj_start_[m + 1]);
  for (const Pair& c : contacts_) {  // adj_start_[i + 1] is the fill cursor of local body i
    if (bodies.immovable(c.b)) continue;
    const std::uint32_t a = local_[c.a], b = local_[c.b];
    adj_[adj_start_[a + 1]++] = b;
    adj_[adj_start_[b + 1]++] = a;
  }
  for (std::size_t k = 0; k < queue_.size(); ++k) {
    const std::uint32_t u = queue_[k];
    for (std::uint32_t e = adj_start_[u]; e < adj_start_[u + 1]; ++e) {
      const std::uint32_t v = adj_[e];
      if (level_[v] != kUnreached) continue;
      level_[v] = level_[u] + 1;
      queue_.push_back(v);
    }
  }

  std::uint32_t top = 0;
  for (const std::uint32_t u : queue_)
    top = std::max(top, level_[u]);
  const std::uint32_t last = top + 1;  // the bucket of contacts no immovable body reaches
  auto bucket = [&](const Pair& c) {
    return bodies.immovable(c.b) ? 0u : std::min({level_[local_[c.a]], level_[local_[c.b]], last});
  };
  level_count_.assign(last + 2, 0);
  for (const Pair& c : contacts_)
    ++level_count_[bucket(c) + 1];
  for (std::size_t l = 1; l < level_count_.size(); ++l)
    level_count_[l] += level_count_[l - 1];
  resize_buffer(ordered_, contacts_.size());
  for (const Pair& c : contacts_) {
    Pair o = c;
    if (!bodies.immovable(c.b) && level_[local_[c.b]] < level_[local_[c.a]]) std::swap(o.a, o.b);
    ordered_[level_count_[bucket(c)]++] = o;
  }
}

// Each body's immovable contacts, grouped where its first one is and sorted there by when the
// body entered each: the bodies keep the order order_contacts gave them, so one body's several
// contacts reorder only its own, and a contact island's order is the same whatever the others'
// bodies touch (a sort of all of them by body, as before, moved one island's bodies as soon as
// some body anywhere touched two immovable ones).
void ChainResolver::order_entries(StepContext& ctx, std::size_t count) {
  entries_.clear();
  first_entry_.assign(involved_.size(), kUnreached);
  for (std::size_t k = 0; k < count; ++k) {
    const Pair& c = ordered_[k];
    std::uint32_t& first = first_entry_[local_[c.a]];
    if (first == kUnreached) first = static_cast<std::uint32_t>(k);
    entries_.push_back({c, entry_face(ctx, c.a, c.b).entry, first});
  }
  std::sort(entries_.begin(), entries_.end(), [](const Entry& p, const Entry& q) {
    if (p.first != q.first) return p.first < q.first;
    if (p.when != q.when) return p.when < q.when;
    return p.pair.b < q.pair.b;
  });
  for (std::size_t k = 0; k < count; ++k)
    ordered_[k] = entries_[k].pair;
}

}  // namespace chain::detail
