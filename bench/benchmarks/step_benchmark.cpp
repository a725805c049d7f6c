// chainbench_bench: time per step of each engine on the built-in scenes.
//
// Each benchmark builds its scene and engine, steps it through a warm-up (the world settles and
// every buffer reaches its working size), then times single steps. Families are keyed by body
// count where the scene scales, so --benchmark_format=json carries a complexity fit over it.
// Counters: bodies, time per body per step, the share of steps cut short, and every counter the
// engine declares (registry.h), contacts among them.
#include "engine.h"
#include "engine_spec.h"
#include "metrics.h"
#include "registry.h"
#include "scene_library.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace chainbench {
namespace {

struct Family {
  std::string name;  // the benchmark's first name part
  std::string scene;
  std::string size_key;    // the --set key that scales the scene, or empty
  std::vector<int> sizes;  // values of size_key
  std::vector<std::string> sets;
  int warmup;
};

void step_benchmark(benchmark::State& state, const Family& family, const EngineSpec& spec) {
  std::vector<std::string> sets = family.sets;
  if (!family.size_key.empty())
    sets.push_back(family.size_key + "=" + std::to_string(state.range(0)));
  sets.push_back("steps=10000000");  // drivers and windows must outlast the benchmark
  const Scene scene = make_scene(family.scene, sets);
  const auto engine = make_engine(spec, scene);
  int step = 0;
  for (; step < family.warmup; ++step)
    engine->step(step);
  double degraded = 0.0;
  for (auto _ : state) {
    engine->step(step++);
    degraded += engine->degraded();
  }
  const auto bodies = static_cast<double>(scene.bodies.size());
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["bodies"] = bodies;
  // Seconds per body per step (shown as ns); in JSON, seconds.
  state.counters["per_body"] = benchmark::Counter(
      bodies * iterations, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["degraded"] = degraded / iterations;
  // The engine's own counters, gathered over a few more steps outside the timing (some engines
  // count by walking their contacts).
  const std::span<const CounterDef> defs = engine->counter_defs();
  std::vector<double> totals(defs.size(), 0.0);
  constexpr int kCounted = 16;
  for (int k = 0; k < kCounted; ++k) {
    engine->step(step++);
    const std::span<const double> values = engine->counters();
    for (std::size_t c = 0; c < totals.size() && c < values.size(); ++c) {
      totals[c] = defs[c].aggregate == Aggregate::kMax ? std::max(totals[c], values[c])
                                                       : totals[c] + values[c] / kCounted;
    }
  }
  for (std::size_t c = 0; c < defs.size(); ++c)
    state.counters[defs[c].name] = totals[c];
  state.SetComplexityN(static_cast<benchmark::IterationCount>(bodies));
}

// What the harness adds: the first default engine on pyramid base=100, stepped bare (0), or stepped
// with the state read back and every metric of `chainbench run` computed after each step (1).
void harness_benchmark(benchmark::State& state, const EngineSpec& spec) {
  const Scene scene = make_scene("pyramid", {"base=100", "steps=10000000"});
  const auto engine = make_engine(spec, scene);
  const bool metrics = state.range(0) != 0;
  MetricsRecorder recorder(scene, MetricSelection{});
  BodyState before(scene.bodies.size()), after(scene.bodies.size());
  int step = 0;
  for (; step < 60; ++step)
    engine->step(step);
  engine->read_state(before);
  for (auto _ : state) {
    engine->step(step++);
    if (metrics) {
      engine->read_state(after);
      recorder.observe(before, after, step, false);
      std::swap(before, after);
    }
  }
  state.counters["bodies"] = static_cast<double>(scene.bodies.size());
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
  const EngineSpec fastest = default_engines().front();
  // What the tables compare: the engine under test and the reference, by their labels.
  benchmark::AddCustomContext("chainbench_subject", fastest.label());
  benchmark::AddCustomContext("chainbench_reference", default_reference().label());
  benchmark::RegisterBenchmark("harness/pyramid100/metrics",
                               [fastest](benchmark::State& s) { harness_benchmark(s, fastest); })
      ->Arg(0)
      ->Arg(1)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->MinTime(0.5);
  // random_pile is a deep pile (2 sqrt(n) m wide) that the reference engines' default solvers
  // let sink; shallow_pile, five boxes deep with friction, is one they hold, so that there every
  // engine does the same work.
  const std::vector<Family> families = {
      {"stack", "stack", "", {0}, {}, 120},
      {"pyramid", "pyramid", "base", {20, 100}, {}, 60},
      {"many_pyramids", "many_pyramids", "", {0}, {}, 60},
      {"push_row", "push_row", "n", {100, 10'000}, {}, 30},
      {"random_pile", "random_pile", "n", {1'000, 10'000, 100'000, 1'000'000}, {}, 30},
      {"shallow_pile", "random_pile", "n", {10'000}, {"layers=5", "friction=0.5"}, 30},
  };
  // How to build each family's scene, for the tables' accuracy runs (scripts/bench_table.py):
  // "SCENE SIZE_KEY [KEY=VALUE...]".
  for (const Family& family : families) {
    std::string recipe = family.scene + " " + (family.size_key.empty() ? "-" : family.size_key);
    for (const std::string& set : family.sets)
      recipe += " " + set;
    benchmark::AddCustomContext("chainbench_family_" + family.name, recipe);
  }
  // Every engine's benchmark settings, named by their labels: pyramid/LABEL/100.
  const auto engines = benchmarked(engine_list);
  for (const Family& family : families) {
    // The smallest size stands for the family when asking what its scenes need.
    std::vector<std::string> smallest = family.sets;
    if (!family.size_key.empty())
      smallest.push_back(family.size_key + "=" + std::to_string(family.sizes.front()));
    const Scene sample = make_scene(family.scene, smallest);
    for (const auto& [spec, max_bodies] : engines) {
      if (!missing_capability(spec, sample).empty()) continue;  // e.g. friction it does not have
      {
        auto* b = benchmark::RegisterBenchmark(
            (family.name + "/" + spec.label()).c_str(),
            [family, spec](benchmark::State& s) { step_benchmark(s, family, spec); });
        b->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
        bool any = false;
        for (const int size : family.sizes) {
          SceneParams params;
          for (const SceneParam& p : all_params(*find_recipe(family.scene)))
            params.set(p.key, p.value);
          for (const std::string& set : family.sets) {
            const std::size_t eq = set.find('=');
            params.set(set.substr(0, eq), std::stod(set.substr(eq + 1)));
          }
          if (!family.size_key.empty()) params.set(family.size_key, size);
          if (find_recipe(family.scene)->body_count(params) > max_bodies) continue;
          b->Arg(size);
          any = true;
        }
        if (any && family.sizes.size() > 1) b->Complexity(benchmark::oN);
      }
    }
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
