// SPDX-License-Identifier: MIT
// Verdicts: what a run did, in words a user can trust. `ok` means physically right (every check
// below passed), not merely finite.
//
// From worst to best:
//   crash       the run's process died (a signal, or an exit without a result)
//   hang        it ran out of time
//   error       it stopped with an error
//   unstable    a position or velocity became non-finite, or a body moved faster in a step than
//               gravity, drivers and initial speeds can make anything move (blow-up)
//   escaped     a body ended farther from its start than anything in the scene could send it
//   tunnelled   a body passed through another
//   wrong       an expectation of the scene failed
//   penetrating two boxes overlapped deeper than the scene's tolerance (default: 5% of the
//               smaller box of the pair)
//   budget      the engine cut some step short to bound its work (the chain solver's budget)
//   ok
#pragma once

#include "judge/expectations.h"
#include "judge/metrics.h"
#include "model/scene.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace chainbench {

enum class VerdictClass : std::uint8_t {
  kSkipped,  // not run: the engine cannot do what the scene needs (stress)
  kOk,
  kBudget,
  kPenetrating,
  kWrong,
  kTunnelled,
  kEscaped,
  kUnstable,
  kError,
  kHang,
  kCrash,
};

const char* to_string(VerdictClass c);

struct Finding {
  VerdictClass what = VerdictClass::kOk;
  std::string detail;  // names the body, the step and the figure: "box2 sank 0.82 m into box1"
  // Where and when, for pages that mark it: the bodies concerned (scene indices, the one that
  // failed first), the state (steps taken; -1 when no one state is to blame) and, for a failed
  // expectation, the body's centre there.
  std::vector<std::size_t> bodies;
  int step = -1;
  std::optional<Vec2d> position;
  // For a failed check with a tolerance (an expectation, a penetration): how far beyond it the
  // worst state went and the tolerance (m, or m/s for at_rest), and whether that is a near miss:
  // within a tenth of the tolerance.
  std::optional<double> margin, tolerance;
  bool near = false;
  friend bool operator==(const Finding&, const Finding&) = default;
};

struct Verdict {
  VerdictClass worst = VerdictClass::kOk;
  std::vector<Finding> findings;  // every failed check, worst first

  bool ok() const { return worst == VerdictClass::kOk; }
  // Every finding is a near miss (so the worst is wrong or penetrating): tallies count these
  // apart from clear failures.
  bool near_miss() const;
  // "ok", or the worst class with its detail: "wrong: expect[0] box2 0.82 m from (0, 2.5)".
  std::string str() const;
  friend bool operator==(const Verdict&, const Verdict&) = default;
};

// Judges a run from its metrics (stability and penetration must have been computed), its
// expectation results and the steps the engine reported as degraded. Null: not judged.
std::optional<Verdict> judge(const Scene& scene, const Metrics& metrics,
                             const std::optional<ExpectResult>& expect,
                             std::uint64_t degraded_steps);

// One line per failed expectation entry, with its margin against its tolerance: "expect[2]
// bounds box3: 0.41 m outside, at (3.41, 0.5) at step 37".
std::string describe(const Scene& scene, const ExpectOutcome& outcome);

}  // namespace chainbench
