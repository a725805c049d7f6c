// SPDX-License-Identifier: MIT
#include "output/replay_recorder.h"

#include "judge/metrics.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace chainbench {
namespace {

std::vector<Vec2d> centres(const Scene& scene) {
  std::vector<Vec2d> c;
  c.reserve(scene.bodies.size());
  for (const SceneBody& b : scene.bodies)
    c.push_back(b.center);
  return c;
}

}  // namespace

ReplayRecorder::ReplayRecorder(const Scene& scene, std::optional<EngineSpec> reference)
    : scene_(scene),
      reference_(std::move(reference)),
      quantum_(replay_quantum(scene)),
      initial_depth_(MetricsRecorder::deepest_overlap(scene, initial_state(scene), 0).depth) {}

void ReplayRecorder::begin(const EngineSpec& spec, std::span<const CounterDef> counters) {
  const bool is_reference = reference_ && spec == *reference_;
  if (reference_ && !is_reference && reference_states_.empty()) {
    throw std::logic_error("replay: the reference " + reference_->label() + " must run first");
  }
  ReplayTrack t(spec, PositionStream(centres(scene_), quantum_));
  t.efd = {0.0};
  t.penetration = {initial_depth_};
  t.ms = {std::numeric_limits<double>::quiet_NaN()};
  if (reference_) t.error_max = t.error_rms = {0.0};
  counted_.clear();
  for (std::size_t c = 0; c < counters.size(); ++c) {
    if (counters[c].aggregate != Aggregate::kSum) continue;
    counted_.push_back(c);
    t.counted.push_back({counters[c].name, counters[c].help, {}});
  }
  if (is_reference) reference_states_ = {centres(scene_)};
  shown_ = centres(scene_);
  tracks_.push_back(std::move(t));
}

void ReplayRecorder::observe(const StepView& v) {
  ReplayTrack& t = tracks_.back();
  // A body out of the world keeps the centre last stored for it (its own as built, before it
  // enters), so that the stream stores nothing for it; the page does not draw it then.
  if (!v.present.empty()) {
    for (std::size_t i = 0; i < shown_.size(); ++i) {
      if (v.present[i]) shown_[i] = v.state->position[i];
    }
  }
  const std::vector<Vec2d>& position = v.present.empty() ? v.state->position : shown_;
  t.positions.add(position);
  double efd = 0.0;
  for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
    if (scene_.bodies[i].kind == BodyKind::kDynamic) efd += v.displacement[i];
  }
  t.efd.push_back(efd);
  double deepest = 0.0;
  for (const double d : v.penetration)
    deepest = std::max(deepest, d);
  t.penetration.push_back(deepest);
  t.ms.push_back(v.ms);
  if (reference_) {
    if (t.spec == *reference_) {
      reference_states_.push_back(position);
      t.error_max.push_back(0.0);
      t.error_rms.push_back(0.0);
    } else {
      const std::size_t k = static_cast<std::size_t>(v.step);
      // A reference that stopped early leaves the later states without a comparison.
      const PositionError e = k < reference_states_.size()
                                  ? position_error(scene_, position, reference_states_[k], v.step)
                                  : PositionError{std::numeric_limits<double>::quiet_NaN(),
                                                  std::numeric_limits<double>::quiet_NaN()};
      t.error_max.push_back(e.max);
      t.error_rms.push_back(e.rms);
    }
  }
  for (const EngineEvent& e : v.events) {
    if (t.events.size() < ReplayTrack::kMaxEvents) {
      t.events.push_back({v.step, e.kind, e.body});
    } else {
      ++t.events_left_out;
    }
  }
  for (std::size_t c = 0; c < counted_.size(); ++c) {
    const std::size_t at = counted_[c];
    if (at < v.counters.size() && v.counters[at] != 0.0)
      t.counted[c].steps.emplace_back(v.step, v.counters[at]);
  }
  if (v.degraded) t.degraded.push_back(v.step);
}

}  // namespace chainbench
