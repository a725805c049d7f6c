#include "drive_schedule.h"

namespace chainbench {

DriveSchedule::DriveSchedule(const Scene& scene) : drivers_(scene.drivers) {
  std::vector<std::int64_t> local_of(scene.bodies.size(), -1);
  for (const Driver& d : drivers_) {
    if (local_of[d.body] < 0) {
      local_of[d.body] = static_cast<std::int64_t>(bodies_.size());
      bodies_.push_back(d.body);
    }
    local_.push_back(static_cast<std::uint32_t>(local_of[d.body]));
  }
  slot_.assign(bodies_.size(), -1);
  was_.assign(bodies_.size(), 0);
  active_.reserve(bodies_.size());
  active_local_.reserve(bodies_.size());
  released_.reserve(bodies_.size());
}

void DriveSchedule::advance(int n) {
  for (const std::uint32_t b : active_local_)
    slot_[b] = -1;
  active_.clear();
  active_local_.clear();
  for (std::size_t k = 0; k < drivers_.size(); ++k) {
    const Driver& d = drivers_[k];
    if (n < d.from_step || n >= d.to_step) continue;
    const Drive drive{d.body, d.velocity, d.hold_x, d.hold_y};
    std::int32_t& slot = slot_[local_[k]];
    if (slot >= 0) {
      active_[static_cast<std::size_t>(slot)] = drive;  // a later driver of the same body wins
    } else {
      slot = static_cast<std::int32_t>(active_.size());
      active_.push_back(drive);
      active_local_.push_back(local_[k]);
    }
  }
  released_.clear();
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const bool now = slot_[b] >= 0;
    if (was_[b] && !now) released_.push_back(bodies_[b]);
    was_[b] = now;
  }
}

}  // namespace chainbench
