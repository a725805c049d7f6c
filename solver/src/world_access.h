// SPDX-License-Identifier: MIT
// A World's parts, for the solver's own tests (tests/solver): what no public function shows, such
// as how often the near pairs were scanned. Not part of the API.
#pragma once

#include "world_impl.h"

namespace chain::detail {

struct WorldAccess {
  static World::Impl& impl(World& world) { return *world.impl_; }
};

}  // namespace chain::detail
