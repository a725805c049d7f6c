// SPDX-License-Identifier: MIT
#include "run/isolated_run.h"

#include "support/child_process.h"
#include "support/input_error.h"

#include <cstring>
#include <deque>
#include <stdexcept>
#include <type_traits>

namespace chainbench {
namespace {

// The bytes a child sends: plain values in the order written, strings and lists with their
// length first. Both ends are this program, so no byte order or version is needed.
class Writer {
 public:
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void str(const std::string& s) {
    pod<std::uint64_t>(s.size());
    out_ += s;
  }
  template <class T>
  void list(std::span<const T> v) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod<std::uint64_t>(v.size());
    out_.append(reinterpret_cast<const char*>(v.data()), v.size_bytes());
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(const std::string& in) : in_(in) {}
  template <class T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, take(sizeof v), sizeof v);
    return v;
  }
  std::string str() {
    const auto n = pod<std::uint64_t>();
    return std::string(take(n), n);
  }
  template <class T>
  std::vector<T> list() {
    const auto n = pod<std::uint64_t>();
    if (n > (in_.size() - at_) / sizeof(T)) throw std::runtime_error("a child's result is cut");
    std::vector<T> v(n);
    const char* bytes = take(n * sizeof(T));
    if (n > 0) std::memcpy(v.data(), bytes, n * sizeof(T));  // an empty vector's data() may be null
    return v;
  }

 private:
  const char* take(std::size_t n) {
    if (n > in_.size() - at_) throw std::runtime_error("a child's result is cut");
    const char* p = in_.data() + at_;
    at_ += n;
    return p;
  }
  const std::string& in_;
  std::size_t at_ = 0;
};

enum class Tag : std::uint8_t { kRun, kInputError, kError };

// Every step the child's run showed its observers, for the caller's.
class StepRecorder final : public StepObserver {
 public:
  void begin(const EngineSpec&, std::span<const CounterDef>) override {}
  void observe(const StepView& v) override {
    ++steps_;
    w_.pod(v.step);
    w_.pod(v.time);
    w_.list(std::span<const Vec2d>(v.state->position));
    w_.list(std::span<const Vec2d>(v.state->velocity));
    w_.list(std::span<const double>(v.state->angle));
    w_.list(v.displacement);
    w_.list(v.penetration);
    w_.list(v.present);
    w_.list(v.counters);
    w_.pod<std::uint64_t>(v.events.size());
    for (const EngineEvent& e : v.events) {
      w_.str(e.kind);
      w_.pod(e.body);
    }
    w_.pod(v.degraded);
  }
  std::uint64_t steps() const { return steps_; }
  std::string take() { return w_.take(); }

 private:
  Writer w_;
  std::uint64_t steps_ = 0;
};

void write_metrics(Writer& w, const Metrics& m) {
  w.pod(m.efd_total), w.pod(m.efd_per_body_step), w.pod(m.efd_max_step);
  w.pod(m.max_penetration), w.pod(m.worst_overlap), w.pod(m.peak_speed);
  w.pod(m.peak_speed_body), w.pod(m.peak_speed_step), w.pod(m.speed_bound);
  w.str(m.speed_unbounded);
  w.pod(m.finite), w.pod(m.blow_up), w.pod(m.tunnelled);
  w.pod(m.blow_up_body), w.pod(m.blow_up_step), w.pod(m.blow_up_speed), w.pod(m.blow_up_bound);
  w.pod(m.in_bounds);
  w.list(std::span<const std::size_t>(m.escaped));
  w.pod(m.tunnel), w.pod(m.tunnel_count);
}

Metrics read_metrics(Reader& r) {
  Metrics m;
  m.efd_total = r.pod<std::optional<double>>();
  m.efd_per_body_step = r.pod<std::optional<double>>();
  m.efd_max_step = r.pod<std::optional<double>>();
  m.max_penetration = r.pod<std::optional<double>>();
  m.worst_overlap = r.pod<std::optional<PairOverlap>>();
  m.peak_speed = r.pod<std::optional<double>>();
  m.peak_speed_body = r.pod<std::size_t>();
  m.peak_speed_step = r.pod<int>();
  m.speed_bound = r.pod<std::optional<double>>();
  m.speed_unbounded = r.str();
  m.finite = r.pod<std::optional<bool>>();
  m.blow_up = r.pod<std::optional<bool>>();
  m.tunnelled = r.pod<std::optional<bool>>();
  m.blow_up_body = r.pod<std::size_t>();
  m.blow_up_step = r.pod<int>();
  m.blow_up_speed = r.pod<double>();
  m.blow_up_bound = r.pod<double>();
  m.in_bounds = r.pod<std::optional<bool>>();
  m.escaped = r.list<std::size_t>();
  m.tunnel = r.pod<std::optional<TunnelEvent>>();
  m.tunnel_count = r.pod<std::uint64_t>();
  return m;
}

// Every field of ExpectResult, in declaration order (EngineRun's operator== and the round-trip
// test in tests/harness/isolated_run_test.cpp catch one left out).
void write_expect(Writer& w, const ExpectResult& e) {
  w.pod(e.max_error), w.pod(e.max_speed_error);
  w.pod(e.pass), w.pod(e.position_pass), w.pod(e.speed_pass);
  w.pod(e.has_position), w.pod(e.has_speed), w.pod(e.near_miss);
  w.list(std::span<const ExpectOutcome>(e.entries));
}

ExpectResult read_expect(Reader& r) {
  ExpectResult e;
  e.max_error = r.pod<double>();
  e.max_speed_error = r.pod<double>();
  e.pass = r.pod<bool>();
  e.position_pass = r.pod<bool>();
  e.speed_pass = r.pod<bool>();
  e.has_position = r.pod<bool>();
  e.has_speed = r.pod<bool>();
  e.near_miss = r.pod<bool>();
  e.entries = r.list<ExpectOutcome>();
  return e;
}

std::string write_run(const EngineRun& run, StepRecorder* steps) {
  Writer w;
  w.pod(Tag::kRun);
  w.list(std::span<const Vec2d>(run.final_positions));
  w.list(std::span<const double>(run.final_angles));
  w.pod(run.timing);
  write_metrics(w, run.metrics);
  w.pod(run.metrics_computed), w.pod(run.hash);
  w.list(std::span<const double>(run.counters));
  w.pod(run.degraded_steps);
  w.pod(run.expect.has_value());
  if (run.expect) write_expect(w, *run.expect);
  w.pod(run.interrupted), w.pod(run.final_state);
  w.pod<std::uint64_t>(run.defs.size());
  for (const CounterDef& d : run.defs) {
    w.str(d.name), w.pod(d.aggregate), w.str(d.help), w.str(d.column);
  }
  w.pod<std::uint64_t>(run.stages.size());
  for (const StageMean& s : run.stages)
    w.str(s.name), w.pod(s.ms);
  w.pod<std::uint64_t>(steps ? steps->steps() : 0);
  std::string out = w.take();
  if (steps) out += steps->take();
  return out;
}

// The run the child sent, with every recorded step handed to the caller's observers.
EngineRun read_run(const Scene& scene, const EngineSpec& spec, const std::string& bytes,
                   const std::vector<StepObserver*>& observers) {
  Reader r(bytes);
  const Tag tag = r.pod<Tag>();
  if (tag == Tag::kInputError) throw InputError(r.str());
  if (tag == Tag::kError) throw std::runtime_error(r.str());
  EngineRun run;
  run.spec = spec;
  run.engine = spec.str();
  run.final_positions = r.list<Vec2d>();
  run.final_angles = r.list<double>();
  run.timing = r.pod<Timing>();
  run.metrics = read_metrics(r);
  run.metrics_computed = r.pod<bool>();
  run.hash = r.pod<std::uint64_t>();
  run.counters = r.list<double>();
  run.degraded_steps = r.pod<std::uint64_t>();
  if (r.pod<bool>()) run.expect = read_expect(r);
  run.interrupted = r.pod<bool>();
  run.final_state = r.pod<int>();
  const auto defs = r.pod<std::uint64_t>();
  for (std::uint64_t k = 0; k < defs; ++k) {
    CounterDef d;
    d.name = r.str();
    d.aggregate = r.pod<Aggregate>();
    d.help = r.str();
    d.column = r.str();
    run.defs.push_back(std::move(d));
  }
  const auto stages = r.pod<std::uint64_t>();
  for (std::uint64_t k = 0; k < stages; ++k) {
    StageMean s;
    s.name = r.str();
    s.ms = r.pod<double>();
    run.stages.push_back(std::move(s));
  }
  // The verdict follows from what came back, as in the child.
  run.verdict = judge(scene, run.metrics, run.expect, run.degraded_steps);
  const auto steps = r.pod<std::uint64_t>();
  for (StepObserver* o : observers)
    o->begin(spec, run.defs);
  std::deque<std::string> kinds;  // EngineEvent::kind points at these
  for (std::uint64_t k = 0; k < steps; ++k) {
    StepView v;
    v.step = r.pod<int>();
    v.time = r.pod<double>();
    BodyState state;
    state.position = r.list<Vec2d>();
    state.velocity = r.list<Vec2d>();
    state.angle = r.list<double>();
    const std::vector<double> displacement = r.list<double>(), penetration = r.list<double>();
    const std::vector<std::uint8_t> present = r.list<std::uint8_t>();
    const std::vector<double> counters = r.list<double>();
    std::vector<EngineEvent> events(r.pod<std::uint64_t>());
    for (EngineEvent& e : events) {
      kinds.push_back(r.str());
      e.kind = kinds.back().c_str();
      e.body = r.pod<std::size_t>();
    }
    v.degraded = r.pod<bool>();
    v.state = &state;
    v.displacement = displacement, v.penetration = penetration, v.counters = counters;
    v.present = present;
    v.events = events;
    for (StepObserver* o : observers)
      o->observe(v);
  }
  return run;
}

// A run that ended without figures: crash, hang or error, and why.
EngineRun failed_run(const EngineSpec& spec, VerdictClass what, std::string why) {
  EngineRun run;
  run.spec = spec;
  run.engine = spec.str();
  run.failure = std::move(why);
  Finding f;
  f.what = what;
  f.detail = spec.label() + " " + *run.failure;
  run.verdict = Verdict{what, {std::move(f)}};
  return run;
}

}  // namespace

std::string encode_run(const EngineRun& run) {
  return write_run(run, nullptr);
}

EngineRun decode_run(const Scene& scene, const EngineSpec& spec, const std::string& bytes) {
  return read_run(scene, spec, bytes, {});
}

EngineRun run_engine_in_child(const Scene& scene, const EngineSpec& spec,
                              const RunOptions& options) {
  std::string bytes;
  const ChildOutcome child = run_in_child_bytes(
      [&] {
        RunOptions inner = options;
        inner.isolate = false;
        inner.step_mark = child_mark();
        StepRecorder steps;
        inner.observers.clear();
        if (!options.observers.empty()) inner.observers.push_back(&steps);
        Writer w;
        try {
          const EngineRun run = run_engine(scene, spec, inner);
          return write_run(run, options.observers.empty() ? nullptr : &steps);
        } catch (const InputError& e) {
          w.pod(Tag::kInputError);
          w.str(e.what());
        } catch (const std::exception& e) {
          w.pod(Tag::kError);
          w.str(e.what());
        }
        return w.take();
      },
      bytes, options.timeout_s, options.stop);
  // Where it was: "at step 12", or nothing before its first step.
  const std::string at = child.mark > 0 ? " at step " + std::to_string(child.mark) : "";
  if (child.finished) {
    try {
      return read_run(scene, spec, bytes, options.observers);
    } catch (const std::exception& e) {
      // Before its first step, a world the plugin would not build for these settings is the
      // user's to fix (InputError, exit 2); once it steps, what goes wrong is the engine's, and
      // its row says so while the other engines' results are kept.
      if (child.mark <= 0) throw;
      return failed_run(spec, VerdictClass::kError, e.what());
    }
  }
  if (child.interrupted) {
    EngineRun run;
    run.spec = spec;
    run.engine = spec.str();
    run.interrupted = true;
    return run;
  }
  return failed_run(spec, child.hang ? VerdictClass::kHang : VerdictClass::kCrash,
                    child_failure(child, options.timeout_s, at));
}

}  // namespace chainbench
