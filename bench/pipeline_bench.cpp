// Throughput of each pipeline stage, printed as rates and as multiples of real time.
// Run: cmake -DGANTRY_BENCH=ON ... && build/bench/gantry_bench
#include <benchmark/benchmark.h>  // the harness
#include <fmt/format.h>           // generated part files

#include <chrono>   // wall time of the threaded pipeline
#include <cstdlib>  // malloc for the counting operator new
#include <ctime>    // clock: the process CPU time
#include <new>      // bad_alloc
#include <random>   // move generation

#include "fusion_style.hpp"  // fusion_style_gcode

#include "gantry/interp/interpreter.hpp"   // Interpreter
#include "gantry/lang/script.hpp"          // Script
#include "gantry/machine/job.hpp"          // run_job
#include "gantry/step/step_generator.hpp"  // StepGenerator
#include "sim/sim_card.hpp"                // SimCard

namespace {

// Heap allocations counted, to show the step generator's steady state allocates nothing.
std::uint64_t g_allocations = 0;

}  // namespace

// GCC sees malloc/free pairs in a replaced operator new/delete as mismatched; they are not.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace {

using namespace gantry;

// `head`, then `lines` moves wandering inside the default table, each `line` formatted.
std::string wandering(int lines, std::string head,
                      fmt::format_string<double, double, double> line) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> x(1, 23), y(1, 17), z(-0.5, 0.5);
  for (int i = 0; i < lines; ++i) head += fmt::format(line, x(rng), y(rng), z(rng));
  return head;
}

std::string generated_file(int lines) {  // M3 moves
  return wandering(lines, "SA\nMS, 4, 2\n", "M3, {:.4f}, {:.4f}, {:.4f}\n");
}

std::string generated_gcode(int lines) {  // G1 blocks
  return wandering(lines, "G20 G90 F240\n", "G1 X{:.4f} Y{:.4f} Z{:.4f}\n");
}

class NullSink : public MotionSink {
 public:
  void move(const CanonMove&) override {}
  void flush() override {}
};

// Loads `text` as `name` (.nc: G-code) with its syntax pass and runs it into a null sink;
// returns the statements run.
std::uint64_t run_text(const Settings& settings, const std::string& text, const char* name) {
  NullSink sink;
  std::string printed;
  ScriptedIO io(true, {}, &printed);
  PersistentStore store;
  Interpreter interp(settings, sink, io, store);
  interp.run(Script::from_text(text, name));
  return interp.statements_executed();
}

// run_text once an iteration; reports `lines` a pass per second.
void interpret_text(benchmark::State& state, const std::string& text, double lines,
                    const char* name = "bench.sbp") {
  const Settings settings = default_settings();
  for (auto _ : state) benchmark::DoNotOptimize(run_text(settings, text, name));
  state.counters["lines/s"] = benchmark::Counter(lines * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}

// The load pass alone (label index and syntax check of every line).
void load_text(benchmark::State& state, const std::string& text, double lines, const char* name) {
  for (auto _ : state) benchmark::DoNotOptimize(Script::from_text(text, name)->ok());
  state.counters["lines/s"] = benchmark::Counter(lines * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}

// Simple lines: `M3, x, y, z` with literal numbers.
void BM_InterpretSimpleLines(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  interpret_text(state, generated_file(n), n);
}
BENCHMARK(BM_InterpretSimpleLines)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_LoadSimpleLines(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  load_text(state, generated_file(n), n, "bench.sbp");
}
BENCHMARK(BM_LoadSimpleLines)->Arg(1000000)->Unit(benchmark::kMillisecond);

// G-code's block parser alone, one reused block (what the interpreter's fast path reads).
void BM_ParseGcodeLines(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto script = Script::from_text(generated_gcode(n), "bench.nc");
  Statement st;
  for (auto _ : state) {
    const std::uint64_t before = g_allocations;
    for (Cursor c = script->start(), next; !script->at_end(c); c = next)
      benchmark::DoNotOptimize(
          parse_gcode_statement(script->line_at(c, &next), script->name(), c.line, &st));
    state.counters["allocations"] = static_cast<double>(g_allocations - before);
  }
  state.counters["lines/s"] =
      benchmark::Counter(static_cast<double>(n) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ParseGcodeLines)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_LoadGcodeLines(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  load_text(state, generated_gcode(n), n, "bench.nc");
}
BENCHMARK(BM_LoadGcodeLines)->Arg(1000000)->Unit(benchmark::kMillisecond);

// G-code blocks interpreted into a null sink (modes, units, soft limits, canonical moves).
void BM_InterpretGcodeLines(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  interpret_text(state, generated_gcode(n), n, "bench.nc");
}
BENCHMARK(BM_InterpretGcodeLines)->Arg(1000000)->Unit(benchmark::kMillisecond);

// Expression-heavy lines in a counted loop with a GOSUB: every line evaluates variables.
void BM_InterpretExpressionLoop(benchmark::State& state) {
  const int loops = static_cast<int>(state.range(0));
  const std::string text = fmt::format(
      "SA\n&i = 0\n&dx = 0.01\n&x0 = 1\nLOOP:\n&i = &i + 1\nGOSUB STEP\n"
      "IF &i < {} THEN GOTO LOOP\nEND\nSTEP:\n&x = &x0 + (&i MOD 100) * &dx\n"
      "M2, &x, 2 + SIN(&i / 10) / 2\nRETURN\n",
      loops);
  interpret_text(state, text, 7.0 * loops);  // lines run per pass, labels included
}
BENCHMARK(BM_InterpretExpressionLoop)->Arg(50000)->Unit(benchmark::kMillisecond);

// A 200k-line file heavy in expressions and GOSUBs: four-line blocks of assignments with
// arithmetic, a comparison, a function call and a GOSUB to a two-line subroutine.
void BM_InterpretExpressionFile(benchmark::State& state) {
  const int blocks = static_cast<int>(state.range(0)) / 4;
  std::string text = "SA\n&i = 0\n&dx = 0.01\n";
  for (int k = 0; k < blocks; ++k)
    text +=
        "&i = &i + 1\n&x = 1 + (&i MOD 100) * &dx\nIF &x > 1.5 THEN &x = &x - 0.5\n"
        "GOSUB CUT\n";
  text += "END\nCUT:\nM2, &x, 2 + SIN(&i / 10) / 2\nRETURN\n";
  interpret_text(state, text, 6.0 * blocks);  // each block also runs the subroutine's 2 lines
}
BENCHMARK(BM_InterpretExpressionFile)->Arg(200000)->Unit(benchmark::kMillisecond);

// A file of distinct lines of every kind a hand-written program has, about `lines` long: each
// eight-line block holds a label, assignments with arithmetic and functions, an IF ... THEN
// GOTO taken on some blocks, a GOSUB to one of ten subroutines (label, assignment, RETURN)
// and an IF ... THEN GOTO never taken; its numbers differ from block to block, so no parse
// is reused. Lines/s counts the statements run, labels included.
std::string mixed_file(int lines) {
  std::string text = "SA\n&a = 1\n&b = 2\n&c = 0\n&d = 0\n";
  for (int k = 0; k < lines / 8; ++k)
    text += fmt::format(
        "L{0}:\n&a = &a + {1}.5 * 2 - ABS(&b - {0})\n&b = (&a MOD {2}) + SQR({3}) / 4\n"
        "IF &b > {4} THEN GOTO S{0}\n&c = &c + 1\nS{0}:\nGOSUB SUB{5}\n"
        "IF &c < 0 THEN GOTO L{0}\n",
        k, k % 97, k % 13 + 3, k % 50 + 1, k % 7 + 3, k % 10);
  text += "END\n";
  for (int s = 0; s < 10; ++s)
    text += fmt::format("SUB{0}:\n&d = &d + SIN(&a / {1}) * {0}\nRETURN\n", s, 100 + s);
  return text;
}

void BM_InterpretMixedFile(benchmark::State& state) {
  const std::string text = mixed_file(static_cast<int>(state.range(0)));
  const Settings settings = default_settings();
  std::uint64_t statements = 0;
  for (auto _ : state) statements += run_text(settings, text, "bench.sbp");
  state.counters["lines/s"] =
      benchmark::Counter(static_cast<double>(statements), benchmark::Counter::kIsRate);
  state.counters["lines"] =  // run per pass
      static_cast<double>(statements) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_InterpretMixedFile)->Arg(200000)->Unit(benchmark::kMillisecond);

class DiscardCard : public Card {
 public:
  void start(double) override {}
  void write(std::span<const std::uint32_t> w) override { ticks_ += w.size(); }
  void drain() override {}
  std::uint64_t ticks_played() const override { return ticks_; }
  void stop(std::uint32_t) override {}
  std::uint32_t inputs() const override { return 0; }
  CardFault fault() const override { return CardFault::None; }

 private:
  std::uint64_t ticks_ = 0;
};

// Step generation alone: six axes moving together at 100 kHz each on the 200 kHz pacer.
void BM_StepGeneratorSixAxesAt100kHz(benchmark::State& state) {
  Settings s = default_settings();
  for (auto& ax : s.axes) {
    ax.steps_per_unit = 10000;  // 10 units/s = 100 kHz
    ax.max_speed = 10;
  }
  const double v = std::sqrt(6.0) * 10;  // one second at 10 units/s per axis
  PlannedSegment seg;
  seg.profile = Trapezoid::plan(v, v, v, v, 1e9);
  DiscardCard card;
  StepGenerator gen(s, card);
  seg.to = Vec6::Zero();
  auto one_second = [&] {  // the generator runs on from segment to segment: steady state
    seg.from = seg.to;
    seg.to = seg.from + Vec6::Constant(10);
    gen.segment(seg);
  };
  one_second();  // warm-up: buffers reach their size
  const std::uint64_t start = card.ticks_played();
  const std::uint64_t allocs_before = g_allocations;
  for (auto _ : state) one_second();
  const auto words = static_cast<double>(card.ticks_played() - start);
  state.counters["allocs_per_s"] =
      static_cast<double>(g_allocations - allocs_before) / static_cast<double>(state.iterations());
  state.counters["words/s"] = benchmark::Counter(words, benchmark::Counter::kIsRate);
  state.counters["x_realtime"] =
      benchmark::Counter(words / s.card.pacer_hz(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StepGeneratorSixAxesAt100kHz)->Unit(benchmark::kMillisecond);

// The whole job on the simulated card in virtual time: machine seconds per WALL second. The
// work runs on the controller's threads (job, feeder), not the benchmark's, so the figures
// are wall time (UseRealTime) and the process's CPU time (MeasureProcessCPUTime); the main
// thread's own CPU time, which is nearly nothing, would make them look a thousand times
// better than they are.
void full_pipeline(benchmark::State& state, const std::string& text, const char* name,
                   double lines) {
  const Settings settings = default_settings();
  double machine_s = 0, wall_s = 0, cpu_s = 0;
  for (auto _ : state) {
    SimCard card(settings);
    std::string printed;
    ScriptedIO io(true, {}, &printed);
    PersistentStore store;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();  // the process's CPU time: every thread's
    const JobResult r = run_job(Script::from_text(text, name), settings, card, io, store);
    wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    cpu_s += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    if (!r.ok()) {
      state.SkipWithError(r.errors.front().message.c_str());
      return;
    }
    machine_s += card.time_s();
  }
  state.counters["x_realtime"] = machine_s / wall_s;  // by wall clock
  // By the process's CPU time (all threads): what a quiet machine's wall clock tends to
  // when the threads do not overlap; on a loaded one it shows the work the load hides.
  state.counters["x_realtime_cpu"] = machine_s / cpu_s;
  state.counters["machine_s"] = machine_s / static_cast<double>(state.iterations());
  state.counters["lines/s"] = lines * static_cast<double>(state.iterations()) / wall_s;
}

// 200 (or more) random M3 moves across the table: long moves, mostly at speed.
void BM_FullPipeline(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  full_pipeline(state, generated_file(n), "bench.sbp", n);
}
BENCHMARK(BM_FullPipeline)
    ->Arg(200)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

// Issue 27's target (>= 2,000x real time): a 35k-line Fusion 360-style adaptive clearing
// job in G-code (bench/fusion_style.hpp): short G1 chords, arcs, feed changes.
void BM_FullPipelineFusion(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  full_pipeline(state, gantry::bench::fusion_style_gcode(n), "fusion.nc", n);
}
BENCHMARK(BM_FullPipelineFusion)
    ->Arg(35000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

}  // namespace
