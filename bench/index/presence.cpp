// SPDX-License-Identifier: MIT
#include "index/presence.h"

#include <algorithm>
#include <utility>

namespace chainbench {

Presence::Presence(const Scene& scene) : scene_(scene), any_(scene.has_lifetimes()) {
  const std::size_t n = scene.bodies.size();
  std::vector<std::pair<int, std::uint32_t>> events;
  for (std::size_t i = 0; i < n && any_; ++i) {
    const SceneBody& b = scene.bodies[i];
    const auto body = static_cast<std::uint32_t>(i);
    // Enters between from_step - 1 and from_step; leaves between to_step and to_step + 1.
    if (b.from_step > 0 && b.from_step <= scene.steps) events.emplace_back(b.from_step, body);
    if (b.to_step < scene.steps) events.emplace_back(b.to_step + 1, body);
  }
  std::sort(events.begin(), events.end());
  for (const auto& [k, body] : events)
    states_.push_back(k), bodies_.push_back(body);
  recompute(0);
}

void Presence::recompute(int k) {
  const std::size_t n = scene_.bodies.size();
  now_.assign(n, 1);
  before_.assign(n, 1);
  dynamic_now_ = dynamic_stepped_ = count_ = stepped_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const SceneBody& b = scene_.bodies[i];
    now_[i] = b.alive(k) ? 1 : 0;
    before_[i] = k > 0 ? (b.alive(k - 1) ? 1 : 0) : now_[i];
    count_ += now_[i];
    stepped_ += now_[i] & before_[i];
    if (b.kind != BodyKind::kDynamic) continue;
    dynamic_now_ += now_[i];
    dynamic_stepped_ += now_[i] & before_[i];
  }
  state_ = k;
  first_ = static_cast<std::size_t>(std::lower_bound(states_.begin(), states_.end(), k) -
                                    states_.begin());
  last_ = static_cast<std::size_t>(std::upper_bound(states_.begin(), states_.end(), k) -
                                   states_.begin());
  if (k == 0) first_ = last_;  // state 0 has no state before it: nothing changed into it
}

void Presence::at(int k) {
  if (!any_ || k == state_) {
    state_ = k;
    return;
  }
  if (k != state_ + 1) {
    recompute(k);
    return;
  }
  // The last move's changes become history: the state before is the state now.
  for (std::size_t e = first_; e < last_; ++e)
    before_[bodies_[e]] = now_[bodies_[e]];
  first_ = last_;
  while (last_ < states_.size() && states_[last_] == k)
    ++last_;
  dynamic_stepped_ = dynamic_now_;
  stepped_ = count_;
  for (std::size_t e = first_; e < last_; ++e) {
    const std::uint32_t i = bodies_[e];
    const bool dynamic = scene_.bodies[i].kind == BodyKind::kDynamic;
    now_[i] ^= 1;
    if (now_[i]) {
      ++count_;
    } else {
      --count_, --stepped_;
    }
    if (!dynamic) continue;
    if (now_[i]) {
      ++dynamic_now_;
    } else {
      --dynamic_now_, --dynamic_stepped_;
    }
  }
  state_ = k;
}

}  // namespace chainbench
