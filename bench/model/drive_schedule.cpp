// SPDX-License-Identifier: MIT
#include "model/drive_schedule.h"

#include <algorithm>

namespace chainbench {

DriveSchedule::DriveSchedule(const Scene& scene) : drivers_(scene.drivers) {
  std::vector<std::int64_t> local_of(scene.bodies.size(), -1);
  std::vector<std::uint32_t> local(drivers_.size());
  for (std::size_t k = 0; k < drivers_.size(); ++k) {
    const Driver& d = drivers_[k];
    if (local_of[d.body] < 0) {
      local_of[d.body] = static_cast<std::int64_t>(bodies_.size());
      bodies_.push_back(d.body);
    }
    local[k] = static_cast<std::uint32_t>(local_of[d.body]);
  }
  // Each body's drivers together, in the scene's order within it (a later driver wins).
  first_driver_.assign(bodies_.size() + 1, 0);
  for (const std::uint32_t b : local)
    ++first_driver_[b + 1];
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    first_driver_[b + 1] += first_driver_[b];
  order_.resize(drivers_.size());
  std::vector<std::uint32_t> fill(first_driver_.begin(), first_driver_.end() - 1);
  for (std::size_t k = 0; k < drivers_.size(); ++k)
    order_[fill[local[k]]++] = static_cast<std::uint32_t>(k);
  for (std::size_t k = 0; k < drivers_.size(); ++k) {
    const Driver& d = drivers_[k];
    if (d.to_step <= d.from_step) continue;  // never active
    events_.push_back({d.from_step, local[k]});
    events_.push_back({d.to_step, local[k]});
  }
  std::sort(events_.begin(), events_.end(), [](const Event& a, const Event& b) {
    return a.step != b.step ? a.step < b.step : a.local < b.local;
  });
  held_.assign(bodies_.size(), 0);
  current_.assign(bodies_.size(), Drive{});
  marked_.assign(bodies_.size(), 0);
  dirty_.reserve(bodies_.size());
  active_.reserve(bodies_.size());
  changed_.reserve(bodies_.size());
  released_.reserve(bodies_.size());
}

void DriveSchedule::settle(std::uint32_t local, int n) {
  const Drive* drive = nullptr;
  Drive found;
  for (std::uint32_t i = first_driver_[local]; i < first_driver_[local + 1]; ++i) {
    const Driver& d = drivers_[order_[i]];
    if (n < d.from_step || n >= d.to_step) continue;
    found = {d.body, d.velocity, d.hold_x, d.hold_y};
    drive = &found;  // a later driver of the same body wins
  }
  const bool was = held_[local] != 0;
  if (!drive) {
    if (was) released_.push_back(bodies_[local]), membership_changed_ = true;
    held_[local] = 0;
    return;
  }
  if (!was || !(current_[local] == *drive)) changed_.push_back(*drive);
  if (!was) membership_changed_ = true;
  held_[local] = 1;
  current_[local] = *drive;
}

void DriveSchedule::advance(int n) {
  changed_.clear();
  released_.clear();
  dirty_.clear();
  if (n <= step_) {
    // Back (or the same step again): every body is worked out afresh, against the step last
    // advanced to, and the events resume after n.
    for (std::uint32_t b = 0; b < bodies_.size(); ++b)
      dirty_.push_back(b);
    next_event_ = static_cast<std::size_t>(
        std::upper_bound(events_.begin(), events_.end(), n,
                         [](int step, const Event& e) { return step < e.step; }) -
        events_.begin());
  } else {
    // Every body with a start or an end in (step_, n]: its drive at n may differ from its drive
    // at step_.
    while (next_event_ < events_.size() && events_[next_event_].step <= n) {
      const std::uint32_t b = events_[next_event_++].local;
      if (!marked_[b]) marked_[b] = 1, dirty_.push_back(b);
    }
    std::sort(dirty_.begin(), dirty_.end());
  }
  for (const std::uint32_t b : dirty_) {
    marked_[b] = 0;
    settle(b, n);
  }
  step_ = n;
  if (membership_changed_) {
    active_.clear();
    for (std::uint32_t b = 0; b < bodies_.size(); ++b) {
      if (held_[b]) active_.push_back(current_[b]);
    }
    membership_changed_ = false;
  } else if (!changed_.empty()) {
    // The same bodies, some with new drives: the active list is in body order, so walk both.
    std::size_t c = 0;
    for (Drive& a : active_) {
      if (c < changed_.size() && changed_[c].body == a.body) a = changed_[c++];
    }
  }
}

}  // namespace chainbench
