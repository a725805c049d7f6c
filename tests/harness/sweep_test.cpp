// SPDX-License-Identifier: MIT
// Sweeps: the Pareto front calls a point faster only by more than the timing spread.
#include "campaign/sweep.h"

#include "engines/engine_spec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

namespace chainbench {
namespace {

SweepPoint point(double ms, double spread, double rms) {
  SweepPoint p;
  p.run.timing.median_ms = ms;
  p.run.timing.spread_ms = spread;
  p.error.rms = rms;
  return p;
}

// Two settings with the same error, 0.15 us apart in median with spreads of 0.5 us: the same
// speed, so both are on the front. 10 us apart, the slower one is not.
TEST(Pareto, SpeedDifferencesWithinTheSpreadAreTies) {
  std::vector<SweepPoint> close = {point(0.01000, 0.0005, 0.1), point(0.01015, 0.0005, 0.1)};
  mark_pareto(close);
  EXPECT_TRUE(close[0].pareto);
  EXPECT_TRUE(close[1].pareto);
  std::vector<SweepPoint> apart = {point(0.010, 0.0005, 0.1), point(0.020, 0.0005, 0.1)};
  mark_pareto(apart);
  EXPECT_TRUE(apart[0].pareto);
  EXPECT_FALSE(apart[1].pareto);
}

// A spread of 0 within a run does not make 0.7 us and 0.6 us different speeds: each median is
// taken as uncertain by at least 5%. 0.6 and 0.5 us are (0.1 us apart, 0.055 us of noise).
TEST(Pareto, NoiseIsAtLeastFivePercentOfTheMedian) {
  EXPECT_DOUBLE_EQ(timing_noise(point(0.0007, 0.0, 0.0).run.timing), 0.05 * 0.0007);
  std::vector<SweepPoint> tie = {point(0.00070, 0.0, 0.0), point(0.00068, 0.0, 0.0)};
  mark_pareto(tie);
  EXPECT_TRUE(tie[0].pareto && tie[1].pareto);
  std::vector<SweepPoint> apart = {point(0.0006, 0.0, 0.0), point(0.0005, 0.0, 0.0)};
  mark_pareto(apart);
  EXPECT_FALSE(apart[0].pareto);
  EXPECT_TRUE(apart[1].pareto);
}

// A more accurate point is on the front however slow; a point that is both slower (beyond noise)
// and less accurate is not; one as fast within noise and more accurate dominates.
TEST(Pareto, AccuracyAndSpeedTogether) {
  std::vector<SweepPoint> p = {point(0.010, 0.001, 0.5), point(1.0, 0.001, 0.01),
                               point(0.050, 0.001, 0.6), point(0.0105, 0.001, 0.4)};
  mark_pareto(p);
  EXPECT_FALSE(p[0].pareto);  // p[3] is as fast within the spreads and more accurate
  EXPECT_TRUE(p[1].pareto);
  EXPECT_FALSE(p[2].pareto);
  EXPECT_TRUE(p[3].pareto);
}

}  // namespace
}  // namespace chainbench

namespace chainbench {
namespace {

// A crashed point measured nothing: its CSV row has empty time and error cells (never 0 ms, which
// would read as the fastest, nor inf) and says crash in its verdict column; its JSON time is null.
TEST(SweepOutput, ACrashedPointHasEmptyFiguresAndSaysCrash) {
  SweepResult r;
  r.scene = "s";
  r.reference = "expect";
  SweepPoint ok = point(0.5, 0.01, 0.1);
  ok.run.spec = parse_engine_spec("chain");
  ok.run.engine = "chain";
  ok.run.verdict = Verdict{};
  SweepPoint crashed;
  crashed.run.spec = ok.run.spec;  // a plugin's spec would load it; the label is not looked at
  crashed.run.engine = "plugin:path=x.so";
  crashed.run.failure = "died of signal 11 (SIGSEGV)";
  crashed.run.verdict = Verdict{VerdictClass::kCrash, {}};
  crashed.error = {HUGE_VAL, HUGE_VAL};
  r.points = {ok, crashed};
  std::ostringstream csv;
  write_sweep_csv(csv, {r});
  std::istringstream lines(csv.str());
  std::string header, first, second;
  std::getline(lines, header), std::getline(lines, first), std::getline(lines, second);
  EXPECT_EQ(header,
            "scene,engine,reference,ms_median,err_max,err_rms,efd_per_body_step,max_penetration,"
            "stable,pareto,vary,verdict");
  EXPECT_EQ(first.substr(first.rfind(',')), ",ok");
  EXPECT_EQ(second, "s,\"plugin:path=x.so\",\"expect\",,,,,,,0,,crash");
  const auto j = sweep_json({r});
  EXPECT_TRUE(j["scenes"][0]["points"][1]["ms_per_step"].is_null());
  EXPECT_EQ(j["scenes"][0]["points"][1]["verdict"], "crash");
  EXPECT_EQ(j["scenes"][0]["points"][0]["ms_per_step"], 0.5);
}

}  // namespace
}  // namespace chainbench
