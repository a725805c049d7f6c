// SPDX-License-Identifier: MIT
// chainbench_bench: time per step of each engine on the built-in scenes.
//
// Each benchmark builds its scene and engine, steps it through a warm-up (the world settles and
// every buffer reaches its working size), then times single steps: as many as Google Benchmark
// needs for a world at rest, or exactly a family's window for a moving scene, so that every
// engine does the same work (families.h). Families are keyed by size where the scene scales, so
// --benchmark_format=json carries a complexity fit over it. Counters: bodies, time per body per
// step, the share of steps cut short, the heap a world holds per body, the median and the slowest
// single step (the worst frame a game budgets for), and every counter the engine declares
// (registry.h), contacts among them. Each step is timed on the steady clock and handed to Google
// Benchmark as manual time, so that the median and the slowest come from the times it sums.
#include "benchmarks/families.h"
#include "benchmarks/pair_judging.h"
#include "engines/engine.h"
#include "engines/engine_spec.h"
#include "engines/registry.h"
#include "index/presence.h"
#include "judge/metrics.h"
#include "run/lifetimes.h"
#include "run/state_feed.h"
#include "scenes/scene_library.h"

#include <benchmark/benchmark.h>
#include <malloc.h>

#ifdef CHAINBENCH_BOX2D3_PLAIN
#include "box2d3/plain_pyramid.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace chainbench {
namespace {

// Bytes the process has allocated and not freed, from the allocator's own books: the same
// measure for every engine, whatever it allocates with (malloc, new, its own block pools on top).
double heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd);
}

// Sums an engine's counters over the steps counted, as each counter's Aggregate says.
class CounterTotals {
 public:
  explicit CounterTotals(const Engine& engine)
      : defs_(engine.counter_defs()), totals_(defs_.size(), 0.0) {}
  void add(const Engine& engine) {
    const std::span<const double> values = engine.counters();
    for (std::size_t c = 0; c < totals_.size() && c < values.size(); ++c) {
      totals_[c] = aggregate_step(defs_[c].aggregate, totals_[c], values[c]);
    }
    ++steps_;
  }
  void report(benchmark::State& state) const {
    for (std::size_t c = 0; c < defs_.size(); ++c) {
      const bool mean = defs_[c].aggregate == Aggregate::kMean && steps_ > 0;
      state.counters[defs_[c].name] = mean ? totals_[c] / steps_ : totals_[c];
    }
  }

 private:
  std::span<const CounterDef> defs_;
  std::vector<double> totals_;
  int steps_ = 0;
};

// The bodies in the world over steps first .. first + steps - 1, on average: those that take
// part in each (presence.h); every body of the scene unless bodies come and go.
double mean_in_world(const Scene& scene, int first, std::int64_t steps) {
  if (!scene.has_lifetimes() || steps <= 0) return static_cast<double>(scene.bodies.size());
  Presence presence(scene);
  double total = 0.0;
  for (std::int64_t k = 0; k < steps; ++k) {
    presence.at(first + static_cast<int>(k) + 1);
    total += static_cast<double>(presence.stepped_count());
  }
  return total / static_cast<double>(steps);
}

void step_benchmark(benchmark::State& state, const Family& family, const EngineSpec& spec) {
  const Scene scene =
      make_scene(family.scene, family_sets(family, static_cast<int>(state.range(0))));
  const double heap_before = heap_in_use();
  const auto engine = make_engine(spec, scene);
  // Bodies that come and go (spawn_rain) are added and removed in the timed step, as in `run`.
  const Lifetimes lives(scene);
  int step = 0;
  for (; step < family.warmup; ++step) {
    lives.apply(*engine, step);
    engine->step(step);
  }
  const double held = heap_in_use() - heap_before;
  Presence at_warmup(scene);
  at_warmup.at(step);
  const auto built = static_cast<double>(at_warmup.count());  // in the world after the warm-up
  CounterTotals counted(*engine);
  double degraded = 0.0;
  std::vector<double> step_ms;
  step_ms.reserve(static_cast<std::size_t>(state.max_iterations));  // no growth while timing
  using Clock = std::chrono::steady_clock;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    lives.apply(*engine, step);
    engine->step(step++);
    const std::chrono::duration<double> took = Clock::now() - t0;
    state.SetIterationTime(took.count());
    step_ms.push_back(1e3 * took.count());
    degraded += engine->degraded();
    // A moving scene: count every timed step, outside the time measured.
    if (family.window > 0) counted.add(*engine);
  }
  const auto iterations = static_cast<double>(state.iterations());
  // Bodies in the world, on average over the timed steps: every body of the scene, except where
  // bodies come and go (spawn_rain), whose scene lists every body that ever enters.
  const double bodies =
      iterations > 0.0 ? mean_in_world(scene, family.warmup, state.iterations()) : built;
  state.counters["bodies"] = bodies;
  // Seconds per body in the world per step (shown as ns); in JSON, seconds.
  state.counters["per_body"] = benchmark::Counter(
      bodies * iterations, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["degraded"] = degraded / iterations;
  state.counters["bytes_per_body"] = held / built;
  // The median step and the slowest, ms: a mean hides the frame that misses a game's budget.
  if (!step_ms.empty()) {
    const auto middle = step_ms.begin() + static_cast<std::ptrdiff_t>(step_ms.size() / 2);
    std::nth_element(step_ms.begin(), middle, step_ms.end());
    state.counters["step_ms_median"] = *middle;
    state.counters["step_ms_max"] = *std::max_element(step_ms.begin(), step_ms.end());
  }
  // A world at rest: its counters over a few more steps (some engines count by walking their
  // contacts, which the timing must not include).
  if (family.window == 0) {
    for (int k = 0; k < 8; ++k) {
      lives.apply(*engine, step);
      engine->step(step++);
      counted.add(*engine);
    }
  }
  counted.report(state);
  state.SetComplexityN(static_cast<benchmark::IterationCount>(std::llround(bodies)));
}

// What the harness adds, on every family and size the engine under test is benchmarked at: the
// engine stepped bare (metrics:0), or stepped with the state read back and every metric of
// `chainbench run` computed after each step (metrics:1). On a moving family also metrics:2, the
// step plus only judging the pairs with a moved body (pair_judging.h): the least any harness that
// judges them every step can add. Named harness/FAMILY/SIZE/metrics:K, so that
// scripts/bench_table.py can put them side by side. The recorder is built before the timing, as
// `run` builds it before the first step.
// harness/FAMILY/SIZE/metrics:2: each step of the window, the state read back, and the judging
// of the step's pairs.
void pair_judging_benchmark(benchmark::State& state, const Family& family, const Scene& scene,
                            const EngineSpec& spec) {
  PairJudging judging(scene, spec, family.warmup, family.window);
  const auto engine = make_engine(spec, scene);
  const Lifetimes lives(scene);
  StateFeed feed(*engine, scene.bodies.size());
  int step = 0;
  for (; step < family.warmup; ++step) {  // as PairJudging and `run` step
    lives.leave(*engine, step);
    engine->step(step);
    lives.enter(*engine, step + 1);
  }
  feed.read();
  int k = 0;
  for (auto _ : state) {
    lives.leave(*engine, step);
    engine->step(step++);
    lives.enter(*engine, step);
    feed.read();
    benchmark::DoNotOptimize(judging.judge(k++, feed.before(), feed.after()));
  }
  state.counters["bodies"] = mean_in_world(scene, family.warmup, state.iterations());
  state.counters["pairs_per_step"] = judging.pairs_per_step();
}

void harness_benchmark(benchmark::State& state, const Family& family, int size,
                       const EngineSpec& spec) {
  const Scene scene = make_scene(family.scene, family_sets(family, size));
  const auto engine = make_engine(spec, scene);
  if (state.range(0) == 2) {
    pair_judging_benchmark(state, family, scene, spec);
    return;
  }
  const bool metrics = state.range(0) != 0;
  std::optional<MetricsRecorder> recorder;
  if (metrics) recorder.emplace(scene, MetricSelection{});
  StateFeed feed(*engine, scene.bodies.size());
  const Lifetimes lives(scene);  // bodies that come and go: added and removed as in `run`
  int step = 0;
  if (metrics) feed.read();  // bare, it steps exactly as step_benchmark does
  for (; step < family.warmup; ++step) {
    lives.leave(*engine, step);
    engine->step(step);
    lives.enter(*engine, step + 1);
    if (metrics) {  // the recorder follows the run from its start, as in `run`
      feed.read();
      recorder->observe(feed.before(), feed.after(), step + 1, false, false, feed.changed());
    }
  }
  for (auto _ : state) {
    lives.leave(*engine, step);
    engine->step(step++);
    lives.enter(*engine, step);
    if (metrics) {
      feed.read();
      recorder->observe(feed.before(), feed.after(), step, false, false, feed.changed());
    }
  }
  // Bodies in the world over the timed steps, as step_benchmark counts them.
  const double bodies = mean_in_world(scene, family.warmup, state.iterations());
  state.counters["bodies"] = bodies;
  state.counters["per_body"] =
      benchmark::Counter(bodies * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

#ifdef CHAINBENCH_BOX2D3_PLAIN
// plain/pyramid/box2d3/BASE: the pyramid family's scene as a Box2D v3 world built by hand with the
// plain v3 API (plain_pyramid.h), at the box2d3 engine's defaults, warmed up and timed as
// step_benchmark times pyramid/box2d3: what the adapter adds is the difference.
void register_plain_box2d3() {
  const Family* pyramid = nullptr;
  for (const Family& family : benchmark_families()) {
    if (family.name == "pyramid") pyramid = &family;
  }
  if (!pyramid) return;
  const EngineSpec defaults = parse_engine_spec("box2d3");
  const auto substeps = static_cast<int>(defaults.get_int("substeps"));
  const int warmup = pyramid->warmup;
  auto* b =
      benchmark::RegisterBenchmark("plain/pyramid/box2d3", [substeps, warmup](benchmark::State& s) {
        PlainBox2d3Pyramid world(static_cast<int>(s.range(0)), substeps);
        for (int k = 0; k < warmup; ++k)
          world.step();
        using Clock = std::chrono::steady_clock;
        for (auto _ : s) {  // timed as step_benchmark times the engines: the step alone
          const auto t0 = Clock::now();
          world.step();
          s.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
        }
        s.counters["bodies"] = static_cast<double>(world.bodies());
      });
  b->Unit(benchmark::kMillisecond)->UseManualTime()->MinTime(0.5);
  for (const int size : pyramid->sizes)
    b->Arg(size);
}
#endif

// The smallest scene of a family, which stands for it when asking what its scenes need: a family's
// sizes differ in counts only, and registration builds nothing large (the scenes a benchmark
// times are built when it runs).
Scene family_sample(const Family& family) {
  return make_scene(family.scene, family_sets(family, family.sizes.front()));
}

// `samples`: family_sample() of each of benchmark_families(), in order.
void register_harness(const EngineSpec& spec, std::size_t max_bodies,
                      const std::vector<Scene>& samples) {
  const std::vector<Family>& families = benchmark_families();
  for (std::size_t k = 0; k < families.size(); ++k) {
    const Family& family = families[k];
    if (!missing_capability(spec, samples[k]).empty()) continue;
    for (const int size : family.sizes) {
      if (family_bodies(family, size) > max_bodies) continue;
      const std::string name = "harness/" + family.name + "/" + std::to_string(size);
      auto* b = benchmark::RegisterBenchmark(
          name.c_str(),
          [family, size, spec](benchmark::State& s) { harness_benchmark(s, family, size, spec); });
      b->ArgName("metrics")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
      if (family.window > 0) {
        b->Arg(2);  // the window's pairs are known in advance only for a fixed window
        b->Iterations(family.window);
      } else {
        b->MinTime(0.5);
      }
      // The ratios of short steps move by 10% between runs of a shared machine: the median of
      // three runs of each. A step of a world this big lasts long enough to be timed once.
      if (family_bodies(family, size) <= 150'000) b->Repetitions(3)->ReportAggregatesOnly(true);
    }
  }
}

// Every registered engine's benchmark settings (EngineDef::benchmarks), or, with
// --chainbench_engines=SPEC,..., those specs (a plugin, say) up to 150,000 bodies.
std::vector<std::pair<EngineSpec, std::size_t>> benchmarked(const std::string& list) {
  std::vector<std::pair<EngineSpec, std::size_t>> out;
  if (!list.empty()) {
    for (EngineSpec& spec : parse_engine_list(list))
      out.emplace_back(std::move(spec), 150'000);
    return out;
  }
  for (const EngineDef& def : engine_registry()) {
    for (const auto& [text, max_bodies] : def.benchmarks)
      out.emplace_back(parse_engine_spec(text), max_bodies);
  }
  return out;
}

void register_all(const std::string& engine_list) {
  const EngineSpec subject = default_engines().front();
  // What the tables compare: the engine under test and the reference, by their labels.
  benchmark::AddCustomContext("chainbench_subject", subject.label());
  benchmark::AddCustomContext("chainbench_reference", default_reference().label());
  // How to build each family's scene, for the tables' accuracy runs (scripts/bench_table.py):
  // "SCENE KEY[,KEY] [KEY=VALUE...]"; which families are moving, and each scaling series' base.
  std::string moving, scaling;
  for (const Family& family : benchmark_families()) {
    std::string keys;
    for (const std::string& key : family.size_keys)
      keys += (keys.empty() ? "" : ",") + key;
    std::string recipe = family.scene + " " + (keys.empty() ? "-" : keys);
    for (const std::string& set : family.sets)
      recipe += " " + set;
    if (family.window > 0) recipe += " steps=" + std::to_string(family.warmup + family.window);
    benchmark::AddCustomContext("chainbench_family_" + family.name, recipe);
    if (family.moving) moving += (moving.empty() ? "" : ",") + family.name;
    if (family.scaling_base > 0) {
      scaling +=
          (scaling.empty() ? "" : ",") + family.name + ":" + std::to_string(family.scaling_base);
    }
  }
  benchmark::AddCustomContext("chainbench_moving", moving);
  // What each engine means by contacts, in its own words.
  for (const EngineDef& def : engine_registry()) {
    for (const CounterDef& counter : def.counters) {
      if (counter.name == "contacts")
        benchmark::AddCustomContext("chainbench_contacts_" + def.name, counter.help);
    }
  }
  benchmark::AddCustomContext("chainbench_scaling", scaling);
  // How an engine's times must be read, for every table that quotes them.
  for (const EngineDef& def : engine_registry()) {
    if (!def.caveat.empty())
      benchmark::AddCustomContext("chainbench_caveat_" + def.name, def.caveat);
  }
  // Every engine's benchmark settings, named by their labels: pyramid/LABEL/100.
  const auto engines = benchmarked(engine_list);
  // Like against like, for the tables' ratios: the engines that skip what rests (sleep=1), whose
  // times are set against the subject's own, and the subject solving every step (skip_rest=0),
  // against which the others' are.
  auto setting = [](const EngineSpec& spec, std::string_view key) {
    for (const auto& [k, v] : spec.settings) {
      if (k == key) return v;
    }
    return std::string();
  };
  std::string sleeping;
  for (const auto& [spec, max_bodies] : engines) {
    if (setting(spec, "sleep") == "1") {
      if (!sleeping.empty()) sleeping += ',';
      sleeping += spec.label();
    }
    if (spec.engine == subject.engine && setting(spec, "skip_rest") == "0" &&
        setting(subject, "skip_rest") == "1") {
      benchmark::AddCustomContext("chainbench_subject_solving", spec.label());
    }
  }
  benchmark::AddCustomContext("chainbench_sleeping", sleeping);
  std::vector<Scene> samples;
  for (const Family& family : benchmark_families())
    samples.push_back(family_sample(family));
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const Family& family = benchmark_families()[k];
    const Scene& sample = samples[k];
    for (const auto& [spec, max_bodies] : engines) {
      if (!missing_capability(spec, sample).empty()) continue;  // e.g. friction it does not have
      const std::size_t most =
          spec.label() == subject.label() ? max_bodies : std::min(max_bodies, family.others_max);
      std::vector<int> sizes;
      for (const int size : family.sizes) {
        if (family_bodies(family, size) <= most) sizes.push_back(size);
      }
      if (sizes.empty()) continue;
      auto* b = benchmark::RegisterBenchmark(
          (family.name + "/" + spec.label()).c_str(),
          [family, spec](benchmark::State& s) { step_benchmark(s, family, spec); });
      b->Unit(benchmark::kMillisecond)->UseManualTime();
      if (family.window > 0) {
        b->Iterations(family.window);
      } else {
        b->MinTime(0.5);
      }
      for (const int size : sizes)
        b->Arg(size);
      if (sizes.size() > 1) b->Complexity(benchmark::oN);
    }
  }
#ifdef CHAINBENCH_BOX2D3_PLAIN
  if (engine_list.empty()) register_plain_box2d3();
#endif
  // The harness' cost, at every size the engine under test runs at.
  for (const auto& [spec, max_bodies] : engines) {
    if (spec.label() == subject.label()) register_harness(spec, max_bodies, samples);
  }
}

}  // namespace
}  // namespace chainbench

int main(int argc, char** argv) {
  // --chainbench_engines=SPEC,... replaces the registered engines' settings; it is ours, not
  // Google Benchmark's, so it is taken out of argv before benchmark::Initialize sees it.
  std::string engines;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::string flag = "--chainbench_engines=";
    if (arg.rfind(flag, 0) == 0) {
      engines = arg.substr(flag.size());
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  try {
    chainbench::register_all(engines);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "chainbench_bench: %s\n", e.what());
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
