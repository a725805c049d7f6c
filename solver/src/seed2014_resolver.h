// SPDX-License-Identifier: MIT
// The 2014 engine's collision chaining, as docs/algorithm-2014.md §2 describes it (its code at
// commit bc64bd3, §0), converted to metres with y up. Kept on purpose, each marked QUIRK in the
// source: the push direction chosen from box edges rather than centres, touching counted as
// overlapping, the extra mass passed asymmetrically, the "chained" short-circuit, no visited
// set, a grid built once per step and never updated, every dynamic pair visited in both orders,
// and a body squeezed between two immovable bodies left inside one of them (it is counted as a
// crush event, not handled). Changed only so that it always terminates and repeats: pairs are
// visited in creation order instead of NSSet's hash order, and a step has a budget of pair
// resolutions and a recursion depth limit, both counted when hit.
#pragma once

#include "step_context.h"

#include <cstdint>
#include <vector>

namespace chain::detail {

class Seed2014Resolver {
 public:
  // `creation_order`: the dynamic slots, oldest body first (the order of dynamicEntities).
  void resolve(StepContext& ctx, const std::vector<std::uint32_t>& creation_order);

 private:
  struct Push {
    double x = 0.0, y = 0.0;
    bool zero() const { return x == 0.0 && y == 0.0; }
  };
  Push resolve_pair(StepContext& ctx, std::uint32_t a, std::uint32_t b, std::uint32_t ignore,
                    double additional_mass, bool force_static, int axis, std::uint32_t depth);
  // Appends the grid neighbours of `body` to near_ (creation order); returns where they start.
  std::size_t gather_near(StepContext& ctx, std::uint32_t body);
  void count_crush(StepContext& ctx, std::uint32_t body, std::uint32_t wall, int axis,
                   std::size_t near_begin);

  std::vector<std::uint32_t> near_;
  std::vector<std::uint8_t> crushed_;
  bool cut_ = false;
};

}  // namespace chain::detail
