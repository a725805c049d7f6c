// SPDX-License-Identifier: MIT
// Bodies, brute-force answers and the size mixes the broadphase tests share.
#pragma once

#include "bodies.h"
#include "broadphase.h"

#include <algorithm>
#include <ostream>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace chain::detail {

using Pairs = std::set<std::pair<std::uint32_t, std::uint32_t>>;

inline Bodies random_bodies(std::uint32_t seed, int n, double spread, double min_half,
                            double max_half) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-spread, spread), half(min_half, max_half), kind(0, 1);
  Bodies b;
  for (int i = 0; i < n; ++i) {
    BodyDef d;
    const double k = kind(rng);
    d.type = k < 0.8 ? BodyType::kDynamic : (k < 0.9 ? BodyType::kKinematic : BodyType::kStatic);
    d.center = {pos(rng), pos(rng)};
    d.half_extents = {half(rng), half(rng)};
    b.append(d, static_cast<std::uint32_t>(i));
  }
  BodyDef ground;
  ground.type = BodyType::kStatic;
  ground.center = {0.0, -spread};
  ground.half_extents = {spread * 2.0, 1.0};
  b.append(ground, static_cast<std::uint32_t>(n));
  std::vector<std::uint32_t> slot_of_id(b.size());
  const std::vector<chain::detail::Origin> origins(b.size(), chain::detail::Origin{});
  b.canonicalize(slot_of_id, origins);
  return b;
}

inline Pairs brute_force(const Bodies& b, double tol) {
  Pairs out;
  for (std::uint32_t i = 0; i < b.size(); ++i) {
    for (std::uint32_t j = i + 1; j < b.size(); ++j) {
      if (b.immovable(i) && b.immovable(j)) continue;
      const double ox = std::min(b.x(i) + b.hx(i), b.x(j) + b.hx(j)) -
                        std::max(b.x(i) - b.hx(i), b.x(j) - b.hx(j));
      const double oy = std::min(b.y(i) + b.hy(i), b.y(j) + b.hy(j)) -
                        std::max(b.y(i) - b.hy(i), b.y(j) - b.hy(j));
      if (ox > tol && oy > tol) out.insert({i, j});
    }
  }
  return out;
}

// Every body's near bodies, as for_each_near_pair gives the pairs.
inline std::vector<std::vector<std::uint32_t>> near_lists(Broadphase& bp, const Bodies& b) {
  std::vector<std::vector<std::uint32_t>> near(b.size());
  bp.for_each_near_pair(b, [&](std::uint32_t i, std::uint32_t j) {
    near[i].push_back(j);
    near[j].push_back(i);
  });
  return near;
}

// The pairs as each body's set of the others.
inline std::vector<std::set<std::uint32_t>> per_body(const Pairs& pairs, std::size_t n) {
  std::vector<std::set<std::uint32_t>> out(n);
  for (const auto& [p, q] : pairs)
    out[p].insert(q), out[q].insert(p);
  return out;
}

struct Mix {
  const char* name;
  int n;
  double spread, min_half, max_half;
};
inline void PrintTo(const Mix& c, std::ostream* os) {
  *os << c.name;
}
// The size mixes every broadphase property is checked on.
inline const Mix kMixes[] = {
    Mix{"UniformDense", 600, 10.0, 0.4, 0.6}, Mix{"MixedSizes", 500, 20.0, 0.05, 3.0},
    Mix{"TinyAndHuge", 300, 50.0, 0.001, 40.0}, Mix{"SparseFarApart", 200, 1.0e5, 0.5, 1.0},
    Mix{"FarFromOrigin", 300, 1.0e6, 0.5, 2000.0}};

}  // namespace chain::detail
