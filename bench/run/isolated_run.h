// SPDX-License-Identifier: MIT
// An engine run in a child process of its own (child_process.h), for engines whose code the
// harness does not own (EngineDef::isolated: plugins): a crash, a hang, an exit without a
// result or an error once it steps becomes the run's verdict (crash, hang or error, with the
// reason and the step) instead of the end of the command. The run's figures, and every step its
// observers would have seen, come back through a pipe as bytes and are handed to the caller's
// observers after the child ends.
#pragma once

#include "run/runner.h"

namespace chainbench {

// run_engine(scene, spec, options) in a child killed after options.timeout_s seconds, or when
// options.stop is set (the run is then marked interrupted). An InputError or other exception in
// the child before its first step (a world the plugin will not build) is thrown again here with
// its message; one from a step on (a failed step, a NaN state) is the run's error verdict.
EngineRun run_engine_in_child(const Scene& scene, const EngineSpec& spec,
                              const RunOptions& options);

// The bytes a child sends for a finished run (without its steps), and the run read back from
// them: decode_run(scene, run.spec, encode_run(run)) == run, field by field, for a finished run
// of `scene` whose verdict is judge()'s (the verdict is judged again from what came back).
std::string encode_run(const EngineRun& run);
EngineRun decode_run(const Scene& scene, const EngineSpec& spec, const std::string& bytes);

}  // namespace chainbench
