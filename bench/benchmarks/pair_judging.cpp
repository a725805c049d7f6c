// SPDX-License-Identifier: MIT
#include "benchmarks/pair_judging.h"

#include "engines/registry.h"
#include "index/presence.h"
#include "judge/metrics.h"
#include "run/lifetimes.h"

#include <utility>

namespace chainbench {

PairJudging::PairJudging(const Scene& scene, const EngineSpec& spec, int warmup, int window)
    : scan_(scene), tunnels_(scene), first_step_(warmup + 1) {
  const auto engine = make_engine(spec, scene);
  const Lifetimes lives(scene);
  Presence presence(scene);  // bodies that come and go: pairs of two bodies in the step only
  // As `run` steps (runner.cpp), warm-up and window alike: the bodies leaving at a step go before
  // it, those entering at the next state come after it. Warmed up with apply() and timed with
  // this, the bodies entering at the first timed step were never added, and the first of them to
  // leave was removed from an engine that never had it.
  int step = 0;
  for (; step < warmup; ++step) {
    lives.leave(*engine, step);
    engine->step(step);
    lives.enter(*engine, step + 1);
  }
  BodyState before = initial_state(scene), after = before;
  engine->read_state(after);
  pairs_.resize(static_cast<std::size_t>(window));
  std::vector<std::uint8_t> moved(scene.bodies.size());
  for (auto& pairs : pairs_) {
    std::swap(before, after);
    lives.leave(*engine, step);
    engine->step(step++);
    lives.enter(*engine, step);
    engine->read_state(after);
    presence.at(step);
    for (std::size_t i = 0; i < moved.size(); ++i) {
      moved[i] = after.position[i].x != before.position[i].x ||
                 after.position[i].y != before.position[i].y;
    }
    scan_.build(before, after);
    scan_.for_each_pair([&](std::size_t i, std::size_t j) {
      if ((moved[i] || moved[j]) && presence.stepped(i) && presence.stepped(j))
        pairs.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
    });
  }
}

double PairJudging::judge(int k, const BodyState& before, const BodyState& after) {
  double depths = 0.0;
  for (const auto& [i, j] : pairs_[static_cast<std::size_t>(k)]) {
    tunnels_.check(before, after, i, j, first_step_ + k);
    depths += scan_.depth(after, i, j);
  }
  tunnels_.end_step();
  return depths;
}

double PairJudging::pairs_per_step() const {
  double total = 0.0;
  for (const auto& p : pairs_)
    total += static_cast<double>(p.size());
  return pairs_.empty() ? 0.0 : total / static_cast<double>(pairs_.size());
}

}  // namespace chainbench
