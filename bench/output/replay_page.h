// SPDX-License-Identifier: MIT
// A replay page: one self-contained HTML file (its data and script inline, nothing fetched) that
// plays every engine's run of a scene over the others, with the charts of their error,
// energy-free displacement and penetration at every step, the scene's expectations, and each
// failed check and engine event marked where and when (docs/replay.md).
//
// Positions are quantised (position_stream.h); when the page would exceed its size limit, only
// every k-th step's positions are kept (the charts keep every step). The page says which.
#pragma once

#include "model/scene.h"
#include "output/replay_recorder.h"
#include "output/report.h"

#include <cstddef>
#include <ostream>
#include <string>

namespace chainbench {

struct ReplayPageOptions {
  std::size_t max_bytes = 20'000'000;        // steps are decimated until the page fits
  std::string generator;                     // "chainbench 0.1.0"
  std::string limit_option = "--replay-mb";  // how the user set max_bytes, for messages
};

struct ReplayPageSummary {
  std::size_t bytes = 0;
  int stride = 1;        // one step in `stride` stored (and the last)
  double quantum = 0.0;  // m
};

// Bodies x states a page holds at most: the recording keeps the reference's positions at every
// state in memory (16 bytes each).
inline constexpr double kMaxReplayBodyStates = 12e6;

// InputError naming the scene when it is too big for a page (kMaxReplayBodyStates).
void check_replay_size(const Scene& scene);

// Writes the page of the runs in `report`, recorded by `recorder`. Throws InputError, before
// writing anything, when even its first and last states do not fit options.max_bytes.
ReplayPageSummary write_replay_page(std::ostream& out, const RunReport& report,
                                    const ReplayRecorder& recorder,
                                    const ReplayPageOptions& options);

}  // namespace chainbench
